#include "api/http_server.hpp"

#include <httplib.h>
#include <sys/socket.h>

#include <atomic>
#include <charconv>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

namespace rangefit::api {

nlohmann::json answer_json(const Answer& answer) {
  nlohmann::json j = answer.body.is_object() ? answer.body : nlohmann::json{{"value", answer.body}};
  j["status"] = to_string(answer.status);
  return j;
}

namespace {

constexpr int kBacklog = 128;

void send(httplib::Response& res, const Answer& answer) {
  res.status = http_status(answer.status);
  if (answer.status == Status::kBusy) res.set_header("Retry-After", "1");
  res.set_content(answer_json(answer).dump(), "application/json");
}

// The backend runs service code: an exception there is a 500 answer, never a dead server thread.
template <class F>
void guarded(httplib::Response& res, F&& f) {
  try {
    send(res, f());
  } catch (const std::exception& e) {
    send(res, error_answer(Status::kError, std::string("internal error: ") + e.what()));
  }
}

std::pair<time_t, time_t> sec_usec(std::chrono::milliseconds ms) {
  return {static_cast<time_t>(ms.count() / 1000), static_cast<time_t>((ms.count() % 1000) * 1000)};
}

// One of the clients waiting for a result, counted while it holds its thread.
class WaitSlot {
 public:
  WaitSlot(std::atomic<int>& waiting, int limit)
      : waiting_(waiting), held_(waiting.fetch_add(1) < limit) {}
  ~WaitSlot() { waiting_.fetch_sub(1); }
  WaitSlot(const WaitSlot&) = delete;
  WaitSlot& operator=(const WaitSlot&) = delete;
  bool held() const { return held_; }

 private:
  std::atomic<int>& waiting_;
  bool held_;
};

}  // namespace

struct HttpServer::Impl {
  Backend& backend;
  HttpOptions options;
  httplib::Server server;
  std::thread thread;
  int port = -1;
  std::atomic<int> waiting{0};  // POST /v1/detect requests waiting for their result

  Impl(Backend& b, HttpOptions o) : backend(b), options(std::move(o)) {}
  void routes();
};

// "Authorization: Bearer TOKEN" (what curl -H and fetch() send), or "X-Rangefit-Token: TOKEN".
std::string token_of(const httplib::Request& req) {
  const std::string auth = req.get_header_value("Authorization");
  if (auth.starts_with("Bearer ")) return auth.substr(7);
  return req.get_header_value("X-Rangefit-Token");
}

void HttpServer::Impl::routes() {
  server.Post("/v1/detect", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] {
      if (!token_matches(options.write_token, token_of(req))) {
        return error_answer(Status::kForbidden,
                            options.write_token.empty()
                                ? "read-only: no token is configured for detection requests"
                                : "detection requests need the configured token "
                                  "(Authorization: Bearer TOKEN)");
      }
      const nlohmann::json request = nlohmann::json::parse(req.body, nullptr, false);
      if (request.is_discarded() || !request.is_object()) {
        return error_answer(Status::kBadRequest, "the body must be one JSON object");
      }
      const std::string wait_param = req.get_param_value("wait");
      if (wait_param == "0" || wait_param == "false") return backend.detect(request, false);
      const WaitSlot slot(waiting, options.max_waiting);
      if (!slot.held()) {
        return error_answer(Status::kBusy, "busy: " + std::to_string(options.max_waiting) +
                                               " clients already wait for their results; retry, "
                                               "or send with ?wait=0 and poll /v1/results/ID");
      }
      return backend.detect(request, true);
    });
  });
  // Ids are the service's own (letters, digits, '-', '_', '.'), so no path can be built from one.
  server.Get(R"(/v1/results/([A-Za-z0-9_.\-]{1,128}))",
             [this](const httplib::Request& req, httplib::Response& res) {
               guarded(res, [&] { return backend.result(req.matches[1]); });
             });
  server.Get(
      R"(/v1/results/([A-Za-z0-9_.\-]{1,128})/([A-Za-z0-9_.]{1,64}))",
      [this](const httplib::Request& req, httplib::Response& res) {
        try {
          const std::string name = req.matches[2];
          const ResultFile* type = result_file_type(name);
          const auto path = type ? backend.result_file(req.matches[1], name) : std::nullopt;
          std::ifstream in;
          if (path) in.open(*path, std::ios::binary);
          if (!in.is_open()) {
            send(res, error_answer(Status::kNotFound, "no " + name + " for this result"));
            return;
          }
          std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
          res.set_content(std::move(bytes), std::string(type->content_type));
        } catch (const std::exception& e) {
          send(res, error_answer(Status::kError, std::string("internal error: ") + e.what()));
        }
      });
  server.Get("/v1/state", [this](const httplib::Request&, httplib::Response& res) {
    guarded(res, [&] { return backend.state(); });
  });
  server.Get("/v1/results", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] {
      std::size_t n = 10;
      const std::string text = req.get_param_value("n");
      if (!text.empty()) {
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
        if (ec != std::errc() || end != text.data() + text.size() || n > 1000) {
          return error_answer(Status::kBadRequest, "n must be a number 0..1000");
        }
      }
      return backend.recent(n);
    });
  });
  for (const StaticFile& f : options.files) {
    const auto serve = [&f](const httplib::Request&, httplib::Response& res) {
      res.set_header("X-Content-Type-Options", "nosniff");
      res.set_header("Cache-Control", "no-cache");
      res.set_content(f.body.data(), f.body.size(), f.content_type.c_str());
    };
    server.Get(f.path, serve);
    if (f.path == "/index.html") server.Get("/", serve);
  }
  // Errors httplib answers itself (no such route, body too large, bad request line) in the
  // same JSON as ours.
  server.set_error_handler(
      httplib::Server::HandlerWithResponse([](const httplib::Request&, httplib::Response& res) {
        if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
        const Status s = res.status == 413   ? Status::kTooLarge
                         : res.status == 404 ? Status::kNotFound
                         : res.status < 500  ? Status::kBadRequest
                                             : Status::kError;
        const int code = res.status;
        send(res, error_answer(s, "HTTP " + std::to_string(code)));
        res.status = code;  // keep httplib's code (405, 414, ...) where ours is coarser
        return httplib::Server::HandlerResponse::Handled;
      }));
}

HttpServer::HttpServer(Backend& backend, HttpOptions options)
    : impl_(std::make_unique<Impl>(backend, std::move(options))) {}

HttpServer::~HttpServer() { stop(); }

bool HttpServer::start(std::string* error) {
  Impl& m = *impl_;
  m.routes();
  m.options.max_waiting = std::max(0, m.options.max_waiting);
  const int threads = std::max(m.options.threads, m.options.max_waiting + kFreeThreads);
  m.server.new_task_queue = [threads] {
    return new httplib::ThreadPool(static_cast<std::size_t>(threads));
  };
  m.server.set_payload_max_length(m.options.max_body_bytes);
  const auto [rs, ru] = sec_usec(m.options.read_timeout);
  const auto [ws, wu] = sec_usec(m.options.write_timeout);
  m.server.set_read_timeout(rs, ru);
  m.server.set_write_timeout(ws, wu);
  m.server.set_keep_alive_max_count(1);  // one request per connection (see the header)
  // httplib listens with a backlog of 5: a burst of clients (50 robots after a cell restart)
  // overflows it and the kernel drops or resets connections. Keep the socket it binds and raise
  // the backlog after its listen() (Linux takes a second listen() as the new backlog).
  int listen_fd = -1;
  // SO_REUSEADDR only: httplib's default also sets SO_REUSEPORT, which would let a second
  // server bind the same port and silently take half the connections.
  m.server.set_socket_options([&listen_fd](int fd) {
    const int one = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    listen_fd = fd;
  });
  const std::string& host = m.options.listen.host;
  if (m.options.listen.port == 0) {
    m.port = m.server.bind_to_any_port(host);
  } else {
    m.port = m.server.bind_to_port(host, m.options.listen.port) ? m.options.listen.port : -1;
  }
  if (m.port >= 0 && listen_fd >= 0) ::listen(listen_fd, kBacklog);
  if (m.port < 0) {
    *error = "http: cannot listen on " + host + ":" + std::to_string(m.options.listen.port);
    return false;
  }
  m.thread = std::thread([&m] { m.server.listen_after_bind(); });
  // stop() before the accept loop runs would not reach it: wait until it does.
  for (int i = 0; i < 2000 && !m.server.is_running(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

void HttpServer::stop() {
  if (!impl_ || !impl_->thread.joinable()) return;
  impl_->server.stop();
  impl_->thread.join();
}

int HttpServer::port() const { return impl_->port; }

}  // namespace rangefit::api
