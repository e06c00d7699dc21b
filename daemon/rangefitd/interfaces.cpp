#include "daemon/rangefitd/interfaces.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "web/page.hpp"

namespace rangefit::daemon {

Interfaces::Interfaces(Service& service, const DaemonConfig& config)
    : service_(service), backend_(service) {
  std::string why;
  if (!config.http.listen.empty()) {
    api::HttpOptions o;
    o.listen = *api::parse_listen_address(config.http.listen, &why);  // checked with the config
    o.write_token = config.http.token;
    o.max_body_bytes = config.http.max_request_bytes;
    // Clients waiting for their result hold a thread each: as many as the queue can hold and
    // the scan running (more would be answered busy by the queue anyway), up to 32; the rest
    // are told busy at the door (or poll with ?wait=0). The threads beyond those serve the
    // page, the state and the results, so a full queue never starves them.
    o.max_waiting =
        static_cast<int>(std::clamp<std::size_t>(config.service.queue_capacity + 1, 1, 32));
    o.threads = o.max_waiting + 2 * api::kFreeThreads;
    for (const web::PageFile& f : web::page_files()) o.files.push_back({f.path, f.type, f.body});
    http_ = std::make_unique<api::HttpServer>(backend_, std::move(o));
  }
  if (!config.tcp.listen.empty()) {
    api::LineOptions o;
    o.listen = *api::parse_listen_address(config.tcp.listen, &why);
    o.write_token = config.tcp.token;
    o.max_line_bytes = config.tcp.max_request_bytes;
    tcp_ = std::make_unique<api::LineServer>(backend_, std::move(o));
  }
}

Interfaces::~Interfaces() { stop(); }

bool Interfaces::start(std::string* error) {
  if (http_) {
    if (!http_->start(error)) return false;
    spdlog::info("http: serving on port {}{}{}", http_->port(),
                 web::page_built() ? ", the page at /" : " (this build has no page: npm missing)",
                 "");
  }
  if (tcp_) {
    if (!tcp_->start(error)) return false;
    spdlog::info("tcp: serving JSON lines on port {}", tcp_->port());
  }
  return true;
}

void Interfaces::stop() {
  service_.board().close();
  if (http_) http_->stop();
  if (tcp_) tcp_->stop();
}

}  // namespace rangefit::daemon
