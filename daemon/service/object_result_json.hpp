#pragma once
// The object detector's account beyond the poses, one form for `rangefit object --json` and the
// service's result details: every instance with its parts' poses and scores (M, I, S, the rank
// sum, the coverage of what the sensor could have measured, grazed samples, size evidence), the
// link errors of a compound object, each rejected candidate's failed check with its value and
// limit, the removed plane, the hypotheses run and the time per stage. Millimetres and radians;
// a part's pose in the scan's frame.

#include <nlohmann/json.hpp>

#include "detect/object/object_detector.hpp"
#include "detect/object/object_model.hpp"

namespace rangefit::daemon {

nlohmann::json object_result_json(const ObjectModel& model, const ObjectDetectResult& r);

// A part's "scores" as object_result_json writes them; what is missing or not a number stays at
// its default (a result file from an older build, or edited by hand).
PartScores part_scores_from_json(const nlohmann::json& scores);

}  // namespace rangefit::daemon
