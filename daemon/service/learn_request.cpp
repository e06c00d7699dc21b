#include "daemon/service/learn_request.hpp"

#include <algorithm>
#include <exception>
#include <numbers>
#include <sstream>
#include <utility>

#include "daemon/service/json_codec.hpp"
#include "io/object_model_file.hpp"

namespace rangefit::daemon {

nlohmann::json learn_json(const LearnResult& r, std::size_t points, std::size_t views) {
  nlohmann::json j;
  j["learnt"] = r.learnt();
  j["reason"] = to_string(r.reason);
  j["name"] = r.model.name;
  j["views"] = views;
  j["points"] = points;
  j["object_points"] = r.segment.object.size();
  j["clusters"] = r.segment.clusters;
  if (r.segment.plane.plane.valid) {
    j["plane"] = {{"removed", r.segment.plane.removed()},
                  {"point", json_vec(r.segment.plane.plane.point)},
                  {"normal", json_vec(r.segment.plane.plane.normal)},
                  {"rms_mm", r.segment.plane.plane.rms}};
  }
  nlohmann::json parts = nlohmann::json::array();
  for (const LearntPart& p : r.parts) {
    nlohmann::json part = pose_json(p.T_world_part);
    part.update({{"name", p.name},
                 {"size", {p.shape.a1, p.shape.a2, p.shape.a3}},
                 {"shape", {p.shape.eps1, p.shape.eps2}},
                 {"taper", {p.shape.kx, p.shape.ky}},
                 {"points", p.points},
                 {"M", p.measure},
                 {"residual_mm", p.residual_mm},
                 {"visible_share", p.visible_share},
                 {"iterations", p.iterations}});
    parts.push_back(std::move(part));
  }
  j["parts"] = parts;
  nlohmann::json links = nlohmann::json::array();
  for (const PartLink& l : r.model.links) {
    nlohmann::json link = {{"parts", {r.model.parts[l.first].name, r.model.parts[l.second].name}},
                           {"angle_deg", l.angle_rad * 180.0 / std::numbers::pi},
                           {"distance_mm", l.distance_mm}};
    if (l.bearing_rad) {
      link["bearing_deg"] = {(*l.bearing_rad)[0] * 180.0 / std::numbers::pi,
                             (*l.bearing_rad)[1] * 180.0 / std::numbers::pi};
    }
    links.push_back(std::move(link));
  }
  j["links"] = links;
  j["starts"] = r.starts;
  j["time_ms"] = r.total_ms;
  return j;
}

std::string learn_provenance(const std::string& source, std::uint64_t seed, const LearnResult& r) {
  std::ostringstream c;
  c << "learnt by " << source << " (seed " << seed << ")\n";
  for (const LearntPart& p : r.parts) {
    c << p.name << ": " << p.points << " points, residual " << p.residual_mm << " mm rms, M "
      << p.measure << ", visible share of the surface " << p.visible_share << "\n";
  }
  return c.str();
}

namespace {

// The sensor, or the sensors whose scans were fused: "stripe + pantilt".
std::string sensors_of(const ScanRequest& request) {
  if (request.sensors.empty()) return request.sensor;
  std::string out;
  for (const std::string& s : request.sensors) out += (out.empty() ? "" : " + ") + s;
  return out;
}

}  // namespace

DetectionResult learn_request(const PointCloud& cloud, const ScanRequest& request,
                              std::uint64_t default_seed) {
  LearnOptions o;
  o.parts = request.parts > 0 ? request.parts : 1;
  o.seed = request.seed != 0 ? request.seed : default_seed;
  o.name = request.model.empty() ? "learnt" : request.model;
  const LearnResult r = learn_model(cloud.points, o);
  DetectionResult out;
  out.details = learn_json(r, cloud.size(), std::max<std::size_t>(1, request.sensors.size()));
  out.found = r.learnt();
  if (!out.found) {
    out.reason = to_string(r.reason);
    return out;
  }
  // Score: the share of the part's surface the scan saw (how much the fit is constrained).
  for (const LearntPart& p : r.parts)
    out.parts.push_back({p.name, p.T_world_part, p.visible_share, 0});
  std::string text;
  std::istringstream comment(learn_provenance(
      "rangefitd, request " + request.id + " on " + sensors_of(request), o.seed, r));
  for (std::string line; std::getline(comment, line);) text += "# " + line + "\n";
  text += io::format_object_model(r.model);
  try {  // what the service's [[objects]] would read (a name with quotes would not)
    (void)io::parse_object_model(text, "model.toml");
  } catch (const std::exception& e) {
    return DetectionResult::error(request,
                                  std::string("learnt model does not read back: ") + e.what());
  }
  out.files.emplace_back("model.toml", std::move(text));
  return out;
}

}  // namespace rangefit::daemon
