#pragma once
// The HTTP/JSON interface for robot controllers and scripts (cpp-httplib):
//   POST /v1/detect                 body: a detection request; ?wait=0 answers 202 + {"id"} at
//   once;
//                                   needs "Authorization: Bearer TOKEN" (403 without, or when no
//                                   token is configured: the interface is then read-only)
//   GET  /v1/results?n=N            the last N results, newest first
//   GET  /v1/results/ID             the result (202 while it runs, 404 unknown)
//   GET  /v1/results/ID/cloud.ply   the scan of a result, and its picture: .../picture.png
//   GET  /v1/state                  lifecycle state and queue
//   GET  /, /PATH                   the static files given in the options (a browser page)
// Every JSON answer carries "status" as in backend.hpp ("ok", "busy", "timeout", ...), the HTTP
// code matches it (200, 503, 504, ...), and errors say why in "error". Bodies over the limit get
// 413 without being read; a client that stops sending is dropped after the read timeout.
// httplib serves a connection on one thread for as long as it is open, so connections are not
// kept alive: an idle client between two requests would hold a thread as a waiting one does.

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "api/backend.hpp"
#include "api/listen_address.hpp"

namespace rangefit::api {

// A file served as is from memory (the page is compiled in: nothing is read from disk for it).
struct StaticFile {
  std::string path;  // "/index.html" ("/" serves it too), "/app.js", ...
  std::string content_type;
  std::string_view body;  // must outlive the server
};

// Threads an HttpServer keeps beyond its waiting clients, for everything else.
inline constexpr int kFreeThreads = 4;

struct HttpOptions {
  ListenAddress listen;                          // loopback by default; port 0: any free port
  std::size_t max_body_bytes = 64 * 1024;        // a detection request is well under 1 KiB
  std::chrono::milliseconds read_timeout{5000};  // per read: a silent client is dropped after it
  std::chrono::milliseconds write_timeout{5000};
  // Clients that wait for their detection's result (POST /v1/detect without ?wait=0) each hold
  // a server thread until it is there, which may be a whole scan. At most max_waiting wait at
  // once; the next gets 503 busy with Retry-After (it may also ask with ?wait=0 and poll), so
  // the threads beyond them stay free for the state, the results and the page.
  int max_waiting = 4;
  // Requests served at once; more wait in line for a thread. Raised to max_waiting +
  // kFreeThreads when lower.
  int threads = 8;
  std::string write_token;        // empty: read-only (every POST /v1/detect is forbidden)
  std::vector<StaticFile> files;  // the browser page
};

class HttpServer {
 public:
  HttpServer(Backend& backend, HttpOptions options);
  ~HttpServer();  // stops
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds and serves on its own threads; false and *error when the address cannot be bound.
  bool start(std::string* error);
  void stop();
  int port() const;  // the bound port (the free one chosen for port 0)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The JSON both interfaces send: the answer's body with "status" set.
nlohmann::json answer_json(const Answer& answer);

}  // namespace rangefit::api
