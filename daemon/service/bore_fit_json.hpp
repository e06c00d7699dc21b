#pragma once
// The fitted bore's own values beyond the pose, one form for `rangefit bore --json` and the
// service's result details: the entrance plane's normal, whether the refinement and the notch
// re-fit ran, and a cylinder's one-sigma standard errors from its refinement under "sigma"
// (axis_rad, offset_mm, radius_mm; cylinder_sigma in detect/bore/cylinder_lsf.hpp: how well the
// points determine the bore, not how far it is from the truth). A cone or ellipse carries its
// own errors in its shape (bore_shape_json.hpp), so "sigma" here is a refined cylinder's only.

#include <nlohmann/json.hpp>

#include "detect/bore/bore_result.hpp"

namespace rangefit::daemon {

nlohmann::json bore_fit_json(const BoreResult& r);

}  // namespace rangefit::daemon
