#pragma once
// Where a stripe ranger's laser never reached. Its camera looks along another line than its
// laser, and the occupancy grid holds only the surface both saw: a wall whose faces the laser
// grazed leaves just its top there, and the camera's line of sight through the wall below it
// would pass as clear. The laser's own range image says otherwise: every ray of the fan (sweep
// position, angle in the fan) stopped at its first measured surface, and what lies farther along
// that ray is in the laser's shadow, where an unmeasured surface may stand. A line of sight
// through it proves nothing. Nor does one through space no laser plane of the sweep held (before
// its first profile, past its last): a wall beside a sweep that stopped short of it hides what
// stands behind it from the camera and leaves no point of its own.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "detect/common/sensor_view.hpp"

namespace rangefit {

class LaserShadow {
 public:
  LaserShadow() = default;  // nothing is in shadow
  // The range image of `points` as `view`'s laser fan saw them (a linear or rotary sweep with a
  // camera; other views give an empty shadow), in bins about `bin_mm` wide at the points'
  // typical distance.
  // The points must outlive the shadow. `beneath`: the whole scan, the floor the points stand on
  // included, for unlit (empty: `points`).
  LaserShadow(std::span<const Eigen::Vector3d> points, const SensorView& view, double bin_mm,
              std::span<const Eigen::Vector3d> beneath = {});

  // Which returns cast a shadow for a query: a part judged is not hidden by its own surface,
  // which would stand where the scan shows the returns were the part there as posed (a shorter
  // look-alike's top edge shades the strip the posed part claims beyond it). Null: every return.
  using Casts = std::function<bool(const Eigen::Vector3d& point)>;

  bool empty() const { return range_.empty(); }
  // True when the laser ray through p met measured surface (that `casts`) more than `margin_mm`
  // before p: two returns of its bin, so that a lone outlier casts nothing.
  bool shadowed(const Eigen::Vector3d& p, double margin_mm, const Casts& casts = nullptr) const;
  // True when no laser plane of the sweep holds p and no scan point lies in the box's column
  // beneath it (along the axis nearest the fan's direction): whatever stands there was never
  // measured.
  bool unlit(const Eigen::Vector3d& p) const;
  // Walks from `from` towards `to` in steps of `step_mm` after skipping `skip_mm`, within the
  // points' bounding box, and returns the distance of the first point in shadow; negative when
  // there is none. A line that leaves the box through a side (not across the fan's direction)
  // into space no laser plane held is in shadow a step past the box.
  double first_shadowed(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double skip_mm,
                        double step_mm, double margin_mm, const Casts& casts = nullptr,
                        double unlit_reach_mm = INFINITY) const;

 private:
  struct Ray {
    double s = 0.0, u = 0.0;  // sweep position, tangent of the angle in the fan
    double range = 0.0;       // distance from the fan's apex
  };
  std::optional<Ray> ray_of(const Eigen::Vector3d& p) const;
  std::optional<std::size_t> bin_of(double s, double u) const;

  SensorView view_;
  double mid_ = 0.0;                // the sweep position the fan's basis is taken at
  Eigen::Vector3d across_, ahead_;  // the fan's plane at mid_: across it, and towards the points
  Eigen::Vector3d mid_apex_from_pivot_ = Eigen::Vector3d::Zero();  // a rotary sweep's, at mid_
  double s0_ = 0.0, u0_ = 0.0, ds_ = 1.0, du_ = 1.0;
  std::size_t ns_ = 0, nu_ = 0;
  Eigen::Vector3d lo_ = Eigen::Vector3d::Zero(), hi_ = Eigen::Vector3d::Zero();
  std::span<const Eigen::Vector3d> points_;  // the scan, borrowed: it outlives the shadow
  std::vector<float> range_;  // per bin the second nearest return, +inf with fewer than two
  std::vector<std::uint32_t> nearest_;  // ... and its index in points_
  // Columns along the axis nearest the fan's direction, column_mm_ wide, over the extent of the
  // points beneath (across_axes_ the other two): which hold a scan point.
  void mark_columns(std::span<const Eigen::Vector3d> beneath, double bin_mm);
  std::size_t column_of(const Eigen::Vector2d& q) const;  // q within [column_lo_, column_hi_]
  std::array<int, 2> across_axes_{0, 1};
  Eigen::Vector2d column_lo_ = Eigen::Vector2d::Zero(), column_hi_ = Eigen::Vector2d::Zero();
  double column_mm_ = 1.0;
  std::array<std::size_t, 2> columns_{0, 0};
  std::vector<bool> column_seen_;
};

}  // namespace rangefit
