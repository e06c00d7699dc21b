#pragma once
// rangefitd's HTTP and line-TCP interfaces ([http], [tcp] of the config), served from their own
// threads over one ServiceBackend, and the browser page (web/) on the HTTP one.

#include <memory>
#include <string>

#include "api/http_server.hpp"
#include "api/line_server.hpp"
#include "daemon/rangefitd/http_backend.hpp"

namespace rangefit::daemon {

class Interfaces {
 public:
  Interfaces(Service& service, const DaemonConfig& config);
  ~Interfaces();
  // Binds what the config asks for; false and *error when an address cannot be bound.
  bool start(std::string* error);
  // Waiting requests are answered first (Service::stop before this, or they wait their time out).
  void stop();
  int http_port() const { return http_ ? http_->port() : -1; }
  int tcp_port() const { return tcp_ ? tcp_->port() : -1; }

 private:
  Service& service_;
  ServiceBackend backend_;
  std::unique_ptr<api::HttpServer> http_;
  std::unique_ptr<api::LineServer> tcp_;
};

}  // namespace rangefit::daemon
