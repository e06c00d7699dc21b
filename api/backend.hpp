#pragma once
// What the HTTP and line-TCP interfaces ask of the service. Both servers only translate: every
// request goes through one Backend, which the service implements with the same queue its DDS
// requests use, so a busy cell, a timeout or an error reads the same on every interface.

#include <array>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace rangefit::api {

// The files of a finished result that the HTTP interface hands out, and their content types: the
// scan and its picture, and what a learn or calibrate request wrote into its spool entry.
struct ResultFile {
  std::string_view name;
  std::string_view content_type;
};
inline constexpr std::array<ResultFile, 15> kResultFiles = {{
    {"cloud.ply", "application/octet-stream"},
    {"picture.png", "image/png"},
    {"model.toml", "text/plain; charset=utf-8"},
    {"raw_sweep_stripe.txt", "text/plain; charset=utf-8"},
    {"raw_sweep_stripe_2.txt", "text/plain; charset=utf-8"},  // further cameras of one request
    {"raw_sweep_stripe_3.txt", "text/plain; charset=utf-8"},
    {"raw_sweep_stripe_4.txt", "text/plain; charset=utf-8"},
    {"calibration_stripe.toml", "text/plain; charset=utf-8"},
    {"calibration_stripe.toml.report.txt", "text/plain; charset=utf-8"},
    {"css_sphere_scan.txt", "text/plain; charset=utf-8"},
    {"calibration_css.toml", "text/plain; charset=utf-8"},
    {"calibration_css.toml.report.txt", "text/plain; charset=utf-8"},
    {"raw_sweep_pantilt.txt", "text/plain; charset=utf-8"},
    {"calibration_pantilt.toml", "text/plain; charset=utf-8"},
    {"calibration_pantilt.toml.report.txt", "text/plain; charset=utf-8"},
}};

// The entry of kResultFiles named `name`, or nullptr.
inline const ResultFile* result_file_type(std::string_view name) {
  for (const ResultFile& f : kResultFiles) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

enum class Status {
  kOk,          // body: the result, state, ...
  kAccepted,    // queued, body {"id": ...}: poll the result
  kBadRequest,  // malformed JSON or fields
  kForbidden,   // a write (a detection) without the configured token, or with none configured
  kNotFound,    // no such result or file
  kTooLarge,    // request body or line over the limit
  kBusy,        // the queue is full: try again later
  kTimeout,     // the scan or the detection ran out of time
  kError,       // anything else; body {"error": ...}
};

const char* to_string(Status s);  // "ok", "accepted", "bad_request", "forbidden", ...
int http_status(Status s);        // 200, 202, 400, 403, 404, 413, 503, 504, 500

struct Answer {
  Status status = Status::kOk;
  nlohmann::json body = nlohmann::json::object();
};

// {"error": message} with that status.
Answer error_answer(Status status, const std::string& message);

// Write access (a detection request): true when a token is configured and given is it. Without
// a configured token the interfaces are read-only.
bool token_matches(const std::string& expected, const std::string& given);

// The servers call these from their worker threads, several at once.
class Backend {
 public:
  virtual ~Backend() = default;
  // A detection request, as `rangefit request` and the spool's request.json spell it. wait: answer
  // when the result is there (kOk, body = the result JSON) or with kBusy / kTimeout / kError;
  // otherwise kAccepted with {"id": ...} as soon as it is queued (or kBusy).
  virtual Answer detect(const nlohmann::json& request, bool wait) = 0;
  // A result by request id: kOk with the result, kAccepted while it runs, kNotFound.
  virtual Answer result(const std::string& id) = 0;
  // The last n finished results, newest first: kOk with {"results": [...]}.
  virtual Answer recent(std::size_t n) = 0;
  // Lifecycle state, queue depth, diagnostics.
  virtual Answer state() = 0;
  // A file of a finished result, one of kResultFiles (the servers ask for no other); nullopt
  // when there is none. The service only returns paths inside its spool.
  virtual std::optional<std::filesystem::path> result_file(const std::string& id,
                                                           const std::string& name) = 0;
};

}  // namespace rangefit::api
