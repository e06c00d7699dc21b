#pragma once
// The service behind the HTTP and TCP interfaces (api/backend.hpp): a request is decoded from
// the JSON the CLI and the spool use (daemon/json_codec.hpp, every field optional but kind),
// admitted through Service::admit, the door DDS requests take, and answered from the result
// board, so busy, timeout and error answers are the very results DDS subscribers get. Files are
// served only from the spool entry of a result the board holds.

#include <atomic>
#include <chrono>
#include <string>

#include "api/backend.hpp"
#include "daemon/rangefitd/service.hpp"

namespace rangefit::daemon {

// A request in the spool's request.json form, mm and rad; absent fields take ScanRequest's
// defaults, an absent or empty id one made here. False and *error on a mistyped field.
bool request_from_json(const nlohmann::json& j, ScanRequest& out, std::string* error);

// How an interface reports a result: ok (found or not found), busy, timeout, bad_request or
// error (by the reason, as `rangefit request` tells them apart), with the result as the body.
api::Answer answer_for(const DetectionResult& result);

class ServiceBackend final : public api::Backend {
 public:
  explicit ServiceBackend(Service& service) : service_(service) {}

  api::Answer detect(const nlohmann::json& request, bool wait) override;
  api::Answer result(const std::string& id) override;
  api::Answer recent(std::size_t n) override;
  api::Answer state() override;
  std::optional<std::filesystem::path> result_file(const std::string& id,
                                                   const std::string& name) override;

 private:
  nlohmann::json result_json(const DetectionResult& r);
  std::string make_id();

  Service& service_;
  std::atomic<std::uint64_t> next_id_{1};
};

}  // namespace rangefit::daemon
