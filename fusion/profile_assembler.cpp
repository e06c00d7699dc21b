#include "fusion/profile_assembler.hpp"

#include <algorithm>
#include <cmath>

namespace rangefit::fusion {

ProfileAssembler::ProfileAssembler(int columns, std::size_t expected_profiles,
                                   hal::Duration profile_period, const TimeLimits& limits)
    : columns_(std::max(columns, 1)),
      expected_profiles_(expected_profiles),
      profile_period_(profile_period),
      limits_(limits) {}

void ProfileAssembler::begin_scan() {
  scan_.reset(expected_profiles_, columns_);
  poses_.clear();
  poses_.reserve(expected_profiles_ * 2);
  frame_check_.reset();
  pending_.clear();
}

std::size_t ProfileAssembler::add_pose(hal::Timestamp stamp, double v0, double v1, bool valid) {
  if (!valid) {
    ++scan_.rejected_reference;
    return 0;
  }
  poses_.push({stamp, v0, v1}, limits_, scan_.faults);
  return drain(false);
}

std::size_t ProfileAssembler::add_profile(const hal::RangerProfile& profile) {
  if (!frame_check_.accept(profile.sequence, profile.stamp, profile_period_, limits_,
                           scan_.faults)) {
    ++scan_.dropped_frames;
    return 0;
  }
  if (pending_.empty() && ready(profile)) {
    fuse(profile);
    return 1;
  }
  pending_.push_back(profile);
  return drain(false);
}

bool ProfileAssembler::ready(const hal::RangerProfile& p) const {
  return !poses_.empty() && poses_.last_stamp() >= p.stamp;
}

std::size_t ProfileAssembler::drain(bool force) {
  std::size_t fused = 0;
  while (!pending_.empty()) {
    if (!force && !ready(pending_.front()) && pending_.size() <= limits_.max_pending_frames) {
      break;
    }
    fuse(pending_.front());
    pending_.pop_front();
    ++fused;
  }
  return fused;
}

void ProfileAssembler::fuse(const hal::RangerProfile& p) {
  if (poses_.empty()) {  // no pose to interpolate or extrapolate from
    ++scan_.faults.extrapolated;
    ++scan_.dropped_frames;
    return;
  }
  const ReferenceTrack::Value pose = ReferenceTrack::Cursor(poses_, p.stamp).at(0.0);
  const Eigen::Isometry3d T = T_world_ranger(pose.v0, pose.v1);
  const Eigen::Vector3d ex = T.linear().col(0);
  const Eigen::Vector3d ez = T.linear().col(2);
  const Eigen::Vector3d origin = T.translation();

  PointCloud& cloud = scan_.cloud;
  const std::size_t row_begin = cloud.grid.index.size();
  cloud.grid.index.resize(row_begin + static_cast<std::size_t>(columns_), -1);
  // Points past the configured columns have no grid cell; they are left out.
  const std::size_t n =
      std::min({p.x_mm.size(), p.z_mm.size(), static_cast<std::size_t>(columns_)});
  for (std::size_t k = 0; k < n; ++k) {
    const double x = p.x_mm[k];
    const double z = p.z_mm[k];
    if (!std::isfinite(x) || !std::isfinite(z)) continue;  // no return
    cloud.grid.index[row_begin + k] = static_cast<std::int32_t>(cloud.points.size());
    cloud.points.push_back(origin + x * ex + z * ez);  // T * (x, 0, z)
    cloud.stamps.push_back(p.stamp);
  }
  if (pose.extrapolated) ++scan_.faults.extrapolated;
  ++cloud.grid.rows;
  scan_.frames.push_back({p.sequence, p.stamp, pose.extrapolated, {pose.v0, pose.v1}});
}

FusedScan ProfileAssembler::finish() {
  drain(true);
  apply_fault_limit(limits_, scan_);
  FusedScan out = std::move(scan_);
  scan_ = FusedScan{};
  scan_.cloud.grid.cols = columns_;
  poses_.clear();
  frame_check_.reset();
  return out;
}

StripeCellAssembler::StripeCellAssembler(const StripeCellFusionConfig& config)
    : ProfileAssembler(config.geometry.ranger.points_per_profile, config.expected_profiles,
                       config.profile_period, config.limits),
      config_(config) {
  begin_scan();
}

PanTiltAssembler::PanTiltAssembler(const PanTiltFusionConfig& config)
    : ProfileAssembler(config.geometry.ranger.points_per_profile, config.expected_profiles,
                       config.profile_period, config.limits),
      config_(config) {
  begin_scan();
}

}  // namespace rangefit::fusion
