#include "daemon/rangefitd/http_backend.hpp"

#include <cctype>
#include <ctime>
#include <system_error>

#include "daemon/dds/messages.hpp"
#include "daemon/service/json_codec.hpp"
#include "daemon/service/result_outcome.hpp"

namespace rangefit::daemon {
namespace fs = std::filesystem;
namespace {

using api::Answer;
using api::Status;

nlohmann::json shape_json(const Superquadric& s) {
  return {{"a1", s.a1},     {"a2", s.a2}, {"a3", s.a3}, {"eps1", s.eps1},
          {"eps2", s.eps2}, {"kx", s.kx}, {"ky", s.ky}};
}

// Waiting longer than the scan and the detection may take means the service is stuck.
std::chrono::milliseconds max_wait(const DaemonConfig& c) {
  return std::chrono::milliseconds(
      static_cast<long>(1000.0 * (c.service.scan_timeout_s + c.detection.timeout_s + 10.0)));
}

}  // namespace

bool request_from_json(const nlohmann::json& j, ScanRequest& out, std::string* error) {
  if (!j.is_object()) {
    *error = "request: must be a JSON object";
    return false;
  }
  if (!j.contains("kind")) {
    *error = "request: \"kind\" (\"bore\" or \"object\") is required";
    return false;
  }
  // Fill in what the client left out with the defaults, then decode as the spool does.
  nlohmann::json full = to_json(ScanRequest{});
  full["id"] = "";
  full.merge_patch(j);
  return from_json(full, out, error);
}

Answer answer_for(const DetectionResult& r) {
  Status status = Status::kOk;
  if (outcome_of(r) == Outcome::kError) {
    const std::string& why = r.reason;
    if (why.starts_with("busy")) {
      status = Status::kBusy;
    } else if (why.starts_with("scan timeout") || why.starts_with("detection timeout")) {
      status = Status::kTimeout;
    } else if (why.starts_with("bad request")) {
      status = Status::kBadRequest;
    } else {
      status = Status::kError;
    }
  }
  nlohmann::json body = to_json(r);
  if (status != Status::kOk) body["error"] = r.reason;
  return {status, body};
}

nlohmann::json ServiceBackend::result_json(const DetectionResult& r) {
  Answer a = answer_for(r);
  // What the page needs to draw the parts, and where the entry's files are.
  if (r.kind == DetectKind::kObject && !r.model.empty()) {
    if (const auto model = service_.model(r.model)) {
      nlohmann::json shapes = nlohmann::json::object();
      for (const ModelPart& p : model->parts) shapes[p.name] = shape_json(p.shape);
      a.body["shapes"] = shapes;
    }
  }
  // A learnt model is drawn as it was learnt (the result's details, as learn_json writes them).
  if (r.kind == DetectKind::kLearn && r.details.is_object() && r.details.contains("parts")) {
    nlohmann::json shapes = nlohmann::json::object();
    for (const auto& p : r.details.at("parts")) {
      const auto& size = p.at("size");
      shapes[p.at("name").get<std::string>()] =
          shape_json({size.at(0).get<double>(), size.at(1).get<double>(), size.at(2).get<double>(),
                      p.at("shape").at(0).get<double>(), p.at("shape").at(1).get<double>(),
                      p.at("taper").at(0).get<double>(), p.at("taper").at(1).get<double>()});
    }
    a.body["shapes"] = shapes;
  }
  nlohmann::json files = nlohmann::json::object();
  for (const api::ResultFile& f : api::kResultFiles) {
    const std::string name(f.name);
    if (result_file(r.request_id, name)) {
      files[name] = "/v1/results/" + r.request_id + "/" + name;
    }
  }
  a.body["files"] = files;
  a.body["status"] = api::to_string(a.status);
  return a.body;
}

std::string ServiceBackend::make_id() {
  return "http-" + std::to_string(std::time(nullptr)) + "-" + std::to_string(next_id_++);
}

Answer ServiceBackend::detect(const nlohmann::json& json, bool wait) {
  ScanRequest request;
  std::string why;
  if (!request_from_json(json, request, &why)) {
    return api::error_answer(Status::kBadRequest, "bad request: " + why);
  }
  if (request.id.empty()) request.id = make_id();
  // Ids name the results' URLs (/v1/results/ID): the characters the routes accept.
  for (const char c : request.id) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
    if (!ok || request.id.size() > 128) {
      return api::error_answer(Status::kBadRequest,
                               "bad request: id must be 1..128 letters, digits, '-', '_' or '.'");
    }
  }
  // The spool's sweep is in mm; the door DDS requests take converts from metres (the wire) for
  // linear sensors: give it the wire's unit.
  const DaemonConfig config = service_.config_copy();
  const std::string sensor = !request.sensor.empty()             ? request.sensor
                             : request.kind == DetectKind::kBore ? config.service.bore_sensor
                                                                 : config.service.object_sensor;
  if (const DeviceConfig* d = config.device(sensor)) {
    convert_sweep_units(request, d->kind->sweep_linear, /*to_wire=*/true);
  }
  if (!service_.board().reserve(request.id)) {
    return api::error_answer(Status::kBadRequest,
                             "bad request: a request with id " + request.id + " is running");
  }
  if (const auto refused = service_.admit(request)) {
    const Answer a = answer_for(*refused);
    return {a.status, result_json(*refused)};
  }
  if (!wait) return {Status::kAccepted, {{"id", request.id}}};
  const auto result = service_.board().wait_for(request.id, max_wait(config));
  if (!result && service_.board().closed()) {
    return api::error_answer(Status::kError, "daemon stopping");
  }
  if (!result) {
    return {Status::kTimeout,
            {{"id", request.id}, {"error", "no result yet; poll /v1/results/" + request.id}}};
  }
  const Answer a = answer_for(*result);
  return {a.status, result_json(*result)};
}

Answer ServiceBackend::result(const std::string& id) {
  DetectionResult r;
  switch (service_.board().find(id, &r)) {
    case ResultBoard::Lookup::kUnknown:
      return api::error_answer(Status::kNotFound, "no result " + id + " (unknown or forgotten)");
    case ResultBoard::Lookup::kPending:
      return {Status::kAccepted, {{"id", id}}};
    case ResultBoard::Lookup::kDone:
      break;
  }
  return {answer_for(r).status, result_json(r)};
}

Answer ServiceBackend::recent(std::size_t n) {
  nlohmann::json list = nlohmann::json::array();
  for (const DetectionResult& r : service_.board().latest(n)) list.push_back(result_json(r));
  return {Status::kOk, {{"results", list}, {"generation", service_.board().generation()}}};
}

Answer ServiceBackend::state() {
  const BoardState board = service_.board().state();
  const DaemonConfig config = service_.config_copy();
  nlohmann::json models = nlohmann::json::array(), sensors = nlohmann::json::array();
  for (const ObjectModelConfig& o : config.objects) models.push_back(o.name);
  for (const DeviceConfig& d : config.devices) {
    if (d.kind->scans) sensors.push_back(d.name);
  }
  const PipelineSnapshot snap = service_.snapshot();
  nlohmann::json diagnostics = nlohmann::json::array();
  for (const DiagStatus& d : board.diagnostics) {
    nlohmann::json values = nlohmann::json::object();
    for (const auto& [k, v] : d.values) values[k] = v;
    static const char* kLevels[] = {"ok", "warn", "error", "stale"};
    diagnostics.push_back({{"name", d.name},
                           {"level", d.level < 4 ? kLevels[d.level] : "?"},
                           {"message", d.message},
                           {"hardware_id", d.hardware_id},
                           {"values", values}});
  }
  return {Status::kOk,
          {{"state", to_string(board.state)},
           {"detail", board.detail},
           {"active_id", board.active_id},
           {"queue_depth", snap.queue_depth},
           {"completed", snap.completed},
           {"rejected_busy", snap.rejected_busy},
           {"last_error", snap.last_error},
           {"stalled", snap.stalled},
           {"generation", service_.board().generation()},
           {"models", models},
           {"sensors", sensors},
           {"diagnostics", diagnostics}}};
}

std::optional<fs::path> ServiceBackend::result_file(const std::string& id,
                                                    const std::string& name) {
  if (api::result_file_type(name) == nullptr) return std::nullopt;
  DetectionResult r;
  if (service_.board().find(id, &r) != ResultBoard::Lookup::kDone || r.spool_entry.empty()) {
    return std::nullopt;
  }
  // Only a regular file directly inside an entry directly inside the spool, links resolved.
  std::error_code ec;
  const fs::path spool = fs::canonical(service_.spool_directory(), ec);
  if (ec) return std::nullopt;
  const fs::path file = fs::canonical(fs::path(r.spool_entry) / name, ec);
  if (ec || !fs::is_regular_file(file, ec) || file.parent_path().parent_path() != spool) {
    return std::nullopt;
  }
  return file;
}

}  // namespace rangefit::daemon
