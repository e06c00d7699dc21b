#include "daemon/service/bore_fit_json.hpp"

namespace rangefit::daemon {

nlohmann::json bore_fit_json(const BoreResult& r) {
  const Eigen::Vector3d& n = r.plane_normal;
  nlohmann::json j = {{"plane_normal", {n.x(), n.y(), n.z()}},
                      {"refined", r.refined},
                      {"second_fit", r.second_fit}};
  // Zero when the refinement did not run or its normal matrix was singular: no estimate.
  if (!r.shape && r.refined && r.sigma_radius > 0.0) {
    j["sigma"] = {{"axis_rad", r.sigma_axis},
                  {"offset_mm", r.sigma_offset},
                  {"radius_mm", r.sigma_radius}};
  }
  return j;
}

}  // namespace rangefit::daemon
