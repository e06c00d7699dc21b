#include "daemon/service/object_result_json.hpp"

#include <type_traits>
#include <utility>

#include "daemon/service/json_codec.hpp"

namespace rangefit::daemon {
namespace {

// Every score with its key, the one list both directions use.
template <class Scores, class F>
void for_each_score(Scores& s, F&& f) {
  f("M", s.measure);
  f("I", s.interior);
  f("S", s.surface);
  f("rank_sum", s.rank_sum);
  f("coverage", s.coverage);
  f("seen_through", s.seen_through);
  f("measurable", s.measurable);
  f("grazed", s.grazed);
  f("facing", s.facing);
  f("size_scale", s.size_scale);
  f("size_determined", s.size_determined);
  f("length_open", s.length_open);
  f("residual_mm", s.residual_mm);
}

nlohmann::json scores_json(const PartScores& s) {
  nlohmann::json j = nlohmann::json::object();
  for_each_score(s, [&](const char* key, const auto& value) { j[key] = value; });
  return j;
}

// A number (a count within range) or a boolean as `out`'s type; anything else leaves it.
template <class T>
void read(const nlohmann::json& j, const char* key, T& out) {
  const auto it = j.find(key);
  if (it == j.end()) return;
  if constexpr (std::is_same_v<T, bool>) {
    if (it->is_boolean()) out = it->get<bool>();
  } else if (it->is_number()) {
    const double v = it->get<double>();
    if constexpr (std::is_integral_v<T>) {
      if (v >= 0.0 && v <= 1e15) out = static_cast<T>(v);
    } else {
      out = v;
    }
  }
}

}  // namespace

PartScores part_scores_from_json(const nlohmann::json& scores) {
  PartScores s;
  if (!scores.is_object()) return s;
  for_each_score(s, [&](const char* key, auto& value) { read(scores, key, value); });
  return s;
}

nlohmann::json object_result_json(const ObjectModel& model, const ObjectDetectResult& r) {
  nlohmann::json j;
  j["hypotheses_evaluated"] = r.hypotheses_evaluated;
  if (r.plane.plane.valid) {
    j["plane"] = {{"removed", r.plane.removed()},
                  {"point", json_vec(r.plane.plane.point)},
                  {"normal", json_vec(r.plane.plane.normal)},
                  {"points", r.plane.plane_points}};
  }
  nlohmann::json instances = nlohmann::json::array();
  for (const DetectedInstance& inst : r.instances) {
    nlohmann::json parts = nlohmann::json::array();
    for (const DetectedPart& p : inst.parts) {
      nlohmann::json part = pose_json(p.T_world_part);
      part["name"] = p.name;
      part["scores"] = scores_json(p.scores);
      parts.push_back(std::move(part));
    }
    instances.push_back({{"parts", parts},
                         {"rank_sum", inst.rank_sum},
                         {"link_angle_error_rad", inst.link_angle_error_rad},
                         {"link_distance_error_mm", inst.link_distance_error_mm},
                         {"link_bearing_error_rad", inst.link_bearing_error_rad}});
  }
  j["instances"] = instances;
  // Not found: which check each candidate failed, its value and the limit it missed.
  nlohmann::json rejections = nlohmann::json::array();
  for (const Rejection& x : r.rejections) {
    rejections.push_back({{"part", model.parts[x.part].name},
                          {"check", to_string(x.check)},
                          {"value", x.value},
                          {"limit", x.limit},
                          {"center", json_vec(x.centre)}});
  }
  j["rejections"] = rejections;
  j["time_ms"] = {{"plane", r.time.plane_ms},
                  {"search_index", r.time.search_index_ms},
                  {"hypotheses", r.time.hypotheses_ms},
                  {"vote", r.time.vote_ms},
                  {"total", r.time.total_ms}};
  return j;
}

}  // namespace rangefit::daemon
