#include "fusion/css_assembler.hpp"

#include <cmath>
#include <optional>

namespace rangefit::fusion {
namespace {

constexpr int kCols = hal::CssRevolution::kSamples;
// Beyond this angle from the revolution's anchor the short series below would lose accuracy;
// at 2 mm/s omega moves ~1e-3 rad per revolution, so one anchor per revolution is the rule.
constexpr double kMaxSeriesAngle = 0.05;

// sin and cos of a small angle d (|d| <= kMaxSeriesAngle): Taylor series to d^7 and d^8, whose
// remainder there is below 1e-17, far under the 1e-9 rad that 0.001 mm at 300 mm needs.
inline void small_sincos(double d, double& s, double& c) {
  const double d2 = d * d;
  s = d * (1.0 - d2 / 6.0 * (1.0 - d2 / 20.0 * (1.0 - d2 / 42.0)));
  c = 1.0 - d2 / 2.0 * (1.0 - d2 / 12.0 * (1.0 - d2 / 30.0 * (1.0 - d2 / 56.0)));
}

}  // namespace

CssAssembler::CssAssembler(const CssFusionConfig& config) : config_(config) {
  const hal::CssGeometry& g = config_.geometry;
  const Eigen::Isometry3d mount = g.T_world_css(0.0);  // R_x(eta) and t of eq. 4.17
  beam_mount_.resize(kCols);
  for (int i = 0; i < kCols; ++i) {
    beam_mount_[i] = mount.linear() * g.beam_direction(g.beam_angle(i, kCols));
  }
  laser_mount_ = mount * g.laser_point();
  begin_scan();
}

void CssAssembler::begin_scan(hal::Timestamp t_start, hal::Timestamp t_end) {
  scan_.reset(config_.expected_revolutions, kCols);
  joints_.clear();
  joints_.reserve(config_.expected_revolutions * 160);  // room for a 1 kHz joint stream
  frame_check_.reset();
  pending_.clear();
  has_last_ = false;
  last_period_ = last_step_ = hal::Duration::zero();

  // Eq. 4.21: v = (d omega / dt) * R, so omega runs from -delta at t_start to +delta at t_end.
  start_from_first_ = t_start == hal::Timestamp::zero();
  t_start_ = t_start;
  end_known_ = t_end > t_start && !start_from_first_;
  t_end_ = t_end;
  const double delta = config_.deflection_rad;
  omega_rate_ = end_known_ ? 2.0 * delta / static_cast<double>((t_end - t_start).count())
                           : config_.scan_speed_mm_s / config_.geometry.pivot_radius_mm * 1e-9;
}

std::size_t CssAssembler::add_joint(const hal::JointSample& sample) {
  if (config_.omega_source != OmegaSource::kJointStream || sample.joint != config_.joint) return 0;
  if (!sample.valid) {
    ++scan_.rejected_reference;
    return 0;
  }
  joints_.push({sample.stamp, sample.angle_rad - config_.omega_zero_rad, 0.0}, config_.limits,
               scan_.faults);
  return drain(false);
}

std::size_t CssAssembler::add_revolution(const hal::CssRevolution& rev) {
  if (!frame_check_.accept(rev.sequence, rev.stamp, last_period_, config_.limits, scan_.faults)) {
    ++scan_.dropped_frames;
    return 0;
  }
  if (has_last_)
    last_step_ =
        (rev.stamp - last_stamp_) / static_cast<std::int64_t>(rev.sequence - last_sequence_);
  has_last_ = true;
  last_stamp_ = rev.stamp;
  last_sequence_ = rev.sequence;
  last_period_ = rev.period;
  const hal::Duration period = rev.period > hal::Duration::zero()   ? rev.period
                               : last_step_ > hal::Duration::zero() ? last_step_
                                                                    : config_.nominal_period;
  if (pending_.empty() && ready(rev, period)) {  // the usual case: no copy
    fuse(rev, period);
    return 1;
  }
  pending_.push_back({rev, period});
  return drain(false);
}

bool CssAssembler::ready(const hal::CssRevolution& rev, hal::Duration period) const {
  if (config_.omega_source != OmegaSource::kJointStream) return true;
  return !joints_.empty() && joints_.last_stamp() >= rev.stamp + period * (kCols - 1) / kCols;
}

std::size_t CssAssembler::drain(bool force) {
  std::size_t fused = 0;
  while (!pending_.empty()) {
    const Pending& p = pending_.front();
    if (!force && !ready(p.revolution, p.period) &&
        pending_.size() <= config_.limits.max_pending_frames) {
      break;
    }
    fuse(p.revolution, p.period);
    pending_.pop_front();
    ++fused;
  }
  return fused;
}

void CssAssembler::fuse(const hal::CssRevolution& rev, hal::Duration period) {
  const bool use_joints = config_.omega_source == OmegaSource::kJointStream;
  if (use_joints && joints_.empty()) {  // nothing to interpolate or extrapolate from
    ++scan_.faults.extrapolated;
    ++scan_.dropped_frames;
    return;
  }
  if (!use_joints && start_from_first_ && scan_.frames.empty()) t_start_ = rev.stamp;

  PointCloud& cloud = scan_.cloud;
  const std::size_t row_begin = cloud.grid.index.size();
  cloud.grid.index.resize(row_begin + kCols, -1);
  FrameInfo info{rev.sequence, rev.stamp, false};

  const hal::CssGeometry& g = config_.geometry;
  const double step_ns = static_cast<double>(period.count()) / kCols;
  const double start_offset_ns = static_cast<double>((rev.stamp - t_start_).count());
  const double end_offset_ns = static_cast<double>((t_end_ - t_start_).count());
  std::optional<ReferenceTrack::Cursor> cursor;
  if (use_joints) cursor.emplace(joints_, rev.stamp);
  bool anchored = false;
  double anchor = 0.0, s0 = 0.0, c0 = 1.0;
  for (int i = 0; i < kCols; ++i) {
    const double r = rev.range_mm[i];
    if (!(r >= g.min_range_mm && r <= g.max_range_mm)) continue;  // also rejects NaN
    const double offset_ns = i * step_ns;
    double omega;
    if (use_joints) {
      const ReferenceTrack::Value v = cursor->at(offset_ns);
      omega = v.v0;
      info.extrapolated |= v.extrapolated;
    } else {  // eq. 4.21
      const double t = start_offset_ns + offset_ns;
      omega = -config_.deflection_rad + omega_rate_ * t;
      info.extrapolated |= t < 0.0 || (end_known_ && t > end_offset_ns);
    }
    double d = omega - anchor;
    if (!anchored || std::abs(d) > kMaxSeriesAngle) {
      anchor = omega;
      s0 = std::sin(omega);
      c0 = std::cos(omega);
      anchored = true;
      d = 0.0;
    }
    double sd, cd;
    small_sincos(d, sd, cd);
    const double s = s0 * cd + c0 * sd;
    const double c = c0 * cd - s0 * sd;
    const Eigen::Vector3d q = laser_mount_ + r * beam_mount_[i];  // R_x * x_s + t, eq. 4.17
    cloud.grid.index[row_begin + i] = static_cast<std::int32_t>(cloud.points.size());
    cloud.points.emplace_back(c * q.x() + s * q.z(), q.y(), c * q.z() - s * q.x());  // eq. 4.19
    cloud.stamps.push_back(rev.stamp + period * i / kCols);
  }
  if (info.extrapolated) ++scan_.faults.extrapolated;
  ++cloud.grid.rows;
  scan_.frames.push_back(info);
}

FusedScan CssAssembler::finish() {
  drain(true);
  apply_fault_limit(config_.limits, scan_);
  FusedScan out = std::move(scan_);
  // Leave an empty scan behind; the next begin_scan() reserves memory again.
  scan_ = FusedScan{};
  scan_.cloud.grid.cols = kCols;
  joints_.clear();
  frame_check_.reset();
  has_last_ = false;
  return out;
}

FusedScan fuse_css_scan(const CssFusionConfig& config,
                        const std::vector<hal::CssRevolution>& revolutions,
                        const std::vector<hal::JointSample>& joints, hal::Timestamp t_start,
                        hal::Timestamp t_end) {
  CssAssembler assembler(config);
  assembler.begin_scan(t_start, t_end);
  for (const hal::JointSample& j : joints) assembler.add_joint(j);
  for (const hal::CssRevolution& r : revolutions) assembler.add_revolution(r);
  return assembler.finish();
}

}  // namespace rangefit::fusion
