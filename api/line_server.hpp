#pragma once
// The line-based TCP interface for controllers that cannot do HTTP (a PLC, a robot program with
// raw sockets): one JSON object per line in, one JSON object per line out, in order.
//   {"op": "detect", "request": {...}, "wait": true}   or the request object itself
//   {"op": "result", "id": "..."}
//   {"op": "state"}
//   {"op": "results", "n": 10}
// A detection needs "token": the configured token, at the top level of the line (in the bare
// request form too); without it, or with no token configured, the answer is forbidden.
// Answers are what the HTTP interface sends (http_server.hpp: answer_json), one per line. Bad
// JSON gets a bad_request answer and the connection stays; a line over the limit gets too_large
// and the connection is closed (the rest of it cannot be framed); an idle client is closed after
// the idle timeout; connections over the limit get one busy answer and are closed.

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>

#include "api/backend.hpp"
#include "api/listen_address.hpp"

namespace rangefit::api {

struct LineOptions {
  ListenAddress listen{"127.0.0.1", 8081};
  std::size_t max_line_bytes = 64 * 1024;
  std::chrono::milliseconds idle_timeout{30000};
  int max_connections = 64;
  std::string write_token;  // empty: read-only
};

class LineServer {
 public:
  LineServer(Backend& backend, LineOptions options);
  ~LineServer();  // stops: closes every connection and joins its thread
  LineServer(const LineServer&) = delete;
  LineServer& operator=(const LineServer&) = delete;

  bool start(std::string* error);
  void stop();
  int port() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One request line to one answer (the protocol without the socket).
Answer answer_line(Backend& backend, const std::string& line, const std::string& write_token);

}  // namespace rangefit::api
