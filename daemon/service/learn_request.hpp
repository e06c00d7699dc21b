#pragma once
// kind = learn: the service teaches an object model from the scan it just took, as `rangefit
// learn` does offline (thesis ch. 6, "show the object once"): the table plane is removed, the
// object segmented and one or two tapered superquadrics fitted (detect/model_learning.hpp). The
// result carries the learnt parts' poses, the parameters and residuals in its details, and the
// model file (model.toml, the format [[objects]] model = ... reads) for the spool entry.

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "daemon/service/scan_types.hpp"
#include "detect/learn/model_learning.hpp"
#include "detect/common/point_cloud.hpp"

namespace rangefit::daemon {

// What `rangefit learn --json` prints and a learn result's details hold (mm, rad, degrees for
// the links' angles as the model file has them): points: the scan's, views: the scans fused.
nlohmann::json learn_json(const LearnResult& r, std::size_t points, std::size_t views);

// The model file's comment header: where it came from and how well the scan supported it.
std::string learn_provenance(const std::string& source, std::uint64_t seed, const LearnResult& r);

// request.model names the model (validation makes it "learnt" when empty), request.parts its
// parts (0: 1), request.seed the seed (0: default_seed).
DetectionResult learn_request(const PointCloud& cloud, const ScanRequest& request,
                              std::uint64_t default_seed);

}  // namespace rangefit::daemon
