#include "fusion/profile_assembler.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

namespace rangefit::fusion {
namespace profile_assembler_test {

using std::chrono::milliseconds;

// A plane n . x = d in the frame of the fused cloud, and the ranger's fan intersected with it.
struct Plane {
  Eigen::Vector3d n;
  double d;
};

struct ProfileTruth {
  std::vector<hal::RangerProfile> profiles;
  std::vector<std::vector<Eigen::Vector3d>> hits;  // world, per profile and point
};

// Casts the fan of `ranger` from pose T_world_ranger onto the plane; returns the profile the
// ranger reports (float x, z) and the exact world hits.
void cast_profile(const hal::StripeRanger& ranger, const Eigen::Isometry3d& T, const Plane& plane,
                  hal::RangerProfile& profile, std::vector<Eigen::Vector3d>& hits) {
  const int n = ranger.points_per_profile;
  profile.x_mm.assign(static_cast<std::size_t>(n), hal::kNoReturn);
  profile.z_mm.assign(static_cast<std::size_t>(n), hal::kNoReturn);
  hits.assign(static_cast<std::size_t>(n), Eigen::Vector3d::Constant(std::nan("")));
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d dir = T.linear() * ranger.ray_direction(k, n);
    const double t = (plane.d - plane.n.dot(T.translation())) / plane.n.dot(dir);
    const Eigen::Vector3d hit = T.translation() + t * dir;
    const Eigen::Vector3d in_ranger = T.inverse() * hit;
    if (t <= 0 || !ranger.depth_in_range(in_ranger.z())) continue;
    profile.x_mm[static_cast<std::size_t>(k)] = static_cast<float>(in_ranger.x());
    profile.z_mm[static_cast<std::size_t>(k)] = static_cast<float>(in_ranger.z());
    hits[static_cast<std::size_t>(k)] = hit;
  }
}

double max_error(const FusedScan& scan, const ProfileTruth& truth) {
  double worst = 0.0;
  for (int r = 0; r < scan.cloud.grid.rows; ++r) {
    for (int c = 0; c < scan.cloud.grid.cols; ++c) {
      const Eigen::Vector3d& hit =
          truth.hits[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
      const std::int32_t k = scan.cloud.grid.at(r, c);
      EXPECT_EQ(k >= 0, !std::isnan(hit.x()));
      if (k < 0 || std::isnan(hit.x())) continue;
      worst = std::max(worst, (scan.cloud.points[static_cast<std::size_t>(k)] - hit).norm());
    }
  }
  return worst;
}

// Sensor cell: the table runs at 6.3 mm/s (thesis maximum), the axis is polled every 10 ms,
// profiles are exposed every 20 ms, 3 ms after an axis sample. The object: an inclined plane.
struct CellScan {
  std::vector<hal::AxisSample> axis;
  ProfileTruth truth;
};

CellScan make_cell_scan(const StripeCellFusionConfig& config, int profiles) {
  const hal::Timestamp t0 = std::chrono::seconds(50);
  const double v = 6.3e-9;  // mm/ns
  const auto position = [&](hal::Timestamp t) {
    return 10.0 + v * static_cast<double>((t - t0).count());
  };
  CellScan s;
  for (hal::Timestamp t = t0 - milliseconds(20); t <= t0 + milliseconds(20) * (profiles + 1);
       t += milliseconds(10)) {
    s.axis.push_back({t, milliseconds(1), position(t), 6.3, 0, 0, true});
  }
  const Plane plane{Eigen::Vector3d(0.0, -0.2, 1.0).normalized(), 40.0};
  for (int p = 0; p < profiles; ++p) {
    hal::RangerProfile profile;
    profile.sequence = static_cast<std::uint32_t>(p);
    profile.stamp = t0 + milliseconds(20) * p + milliseconds(3);
    std::vector<Eigen::Vector3d> hits;
    cast_profile(config.geometry.ranger, config.geometry.T_world_ranger(position(profile.stamp)),
                 plane, profile, hits);
    s.truth.profiles.push_back(std::move(profile));
    s.truth.hits.push_back(std::move(hits));
  }
  return s;
}

FusedScan fuse_cell(const StripeCellFusionConfig& config, const std::vector<hal::AxisSample>& axis,
                    const std::vector<hal::RangerProfile>& profiles) {
  StripeCellAssembler assembler(config);
  for (const auto& a : axis) assembler.add_axis(a);
  for (const auto& p : profiles) assembler.add_profile(p);
  return assembler.finish();
}

TEST(StripeCellAssembler, EveryFusedPointIsWithinAMicrometreOfTheTrueHit) {
  const StripeCellFusionConfig config;
  const CellScan s = make_cell_scan(config, 50);
  const FusedScan scan = fuse_cell(config, s.axis, s.truth.profiles);
  ASSERT_EQ(scan.cloud.grid.rows, 50);
  EXPECT_EQ(scan.cloud.grid.cols, 512);
  EXPECT_GT(scan.cloud.size(), 50u * 500u);
  EXPECT_LT(max_error(scan, s.truth), 0.001);
  EXPECT_EQ(scan.faults.total(), 0u);
}

TEST(StripeCellAssembler, ProfileWaitsForTheAxisSampleAfterItsStamp) {
  const StripeCellFusionConfig config;
  const CellScan s = make_cell_scan(config, 1);
  StripeCellAssembler assembler(config);
  std::size_t a = 0;
  for (; s.axis[a].stamp < s.truth.profiles[0].stamp; ++a) assembler.add_axis(s.axis[a]);
  EXPECT_EQ(assembler.add_profile(s.truth.profiles[0]), 0u);
  EXPECT_EQ(assembler.add_axis(s.axis[a]), 1u);
  EXPECT_LT(max_error(assembler.finish(), s.truth), 0.001);
}

TEST(StripeCellAssembler, EmptyScanGivesAnEmptyCloudWithoutFaults) {
  StripeCellAssembler assembler{StripeCellFusionConfig{}};
  const FusedScan scan = assembler.finish();
  EXPECT_TRUE(scan.cloud.empty());
  EXPECT_EQ(scan.faults.total(), 0u);
  EXPECT_FALSE(scan.bad);
}

StripeCellFusionConfig fault_config() {
  StripeCellFusionConfig config;
  config.profile_period = milliseconds(20);  // enables the clock-jump check from the first step
  return config;
}

// The axis samples for which keep() holds (a copy: the scans are shared by several tests).
template <class Keep>
std::vector<hal::AxisSample> axis_where(const std::vector<hal::AxisSample>& axis, Keep keep) {
  std::vector<hal::AxisSample> out;
  for (const auto& a : axis) {
    if (keep(a)) out.push_back(a);
  }
  return out;
}

TEST(StripeCellTimeFaults, ProfileDeliveredTwiceIsDroppedAndCountedOutOfOrder) {
  const CellScan s = make_cell_scan(fault_config(), 40);
  std::vector<hal::RangerProfile> profiles(s.truth.profiles.begin(), s.truth.profiles.begin() + 10);
  profiles.push_back(s.truth.profiles[8]);
  const FusedScan scan = fuse_cell(fault_config(), s.axis, profiles);
  EXPECT_EQ(scan.faults.out_of_order, 1u);
  EXPECT_EQ(scan.faults.total(), 1u);
  EXPECT_EQ(scan.dropped_frames, 1u);
}

TEST(StripeCellTimeFaults, AxisStreamGapLongerThanTheLimitIsCounted) {
  const CellScan s = make_cell_scan(fault_config(), 40);
  const hal::Timestamp from = s.axis[20].stamp;
  const auto axis = axis_where(s.axis, [&](const hal::AxisSample& a) {
    return a.stamp < from || a.stamp > from + milliseconds(55);  // 70 ms without a sample
  });
  EXPECT_EQ(fuse_cell(fault_config(), axis, s.truth.profiles).faults.gaps, 1u);
}

TEST(StripeCellTimeFaults, ProfilesBeyondTheLastAxisSampleAreExtrapolatedAndCounted) {
  const CellScan s = make_cell_scan(fault_config(), 40);
  const hal::Timestamp stop = s.truth.profiles[36].stamp + milliseconds(10);
  const auto axis = axis_where(s.axis, [&](const hal::AxisSample& a) { return a.stamp <= stop; });
  const FusedScan scan = fuse_cell(fault_config(), axis, s.truth.profiles);
  EXPECT_EQ(scan.faults.extrapolated, 3u);
  EXPECT_FALSE(scan.frames[36].extrapolated);
  EXPECT_TRUE(scan.frames.back().extrapolated);
}

TEST(StripeCellTimeFaults, StampStepAgainstTheProfilePeriodIsAClockJump) {
  const CellScan s = make_cell_scan(fault_config(), 40);
  auto profiles = s.truth.profiles;
  for (std::size_t p = 20; p < profiles.size(); ++p) profiles[p].stamp += milliseconds(5);
  EXPECT_EQ(fuse_cell(fault_config(), s.axis, profiles).faults.clock_jumps, 1u);
}

TEST(StripeCellTimeFaults, InvalidAxisSamplesAreRejectedNotUsed) {
  const CellScan s = make_cell_scan(fault_config(), 40);
  auto axis = s.axis;
  axis[30].valid = false;
  axis[30].position_mm = 1e4;
  const FusedScan scan = fuse_cell(fault_config(), axis, s.truth.profiles);
  EXPECT_EQ(scan.rejected_reference, 1u);
  EXPECT_LT(max_error(scan, s.truth), 0.001);
}

// Mobile head: pan sweeps at 10 deg/s (thesis), tilt held, 100 profiles/s, pan/tilt polled every
// 10 ms 5 ms out of phase with the exposures. The scene: a plane 1 m in front of the head.
TEST(PanTiltAssembler, EveryFusedPointIsWithinAMicrometreOfTheTrueHit) {
  PanTiltFusionConfig config;
  config.geometry.t_s_mm = {10.0, 20.0, 30.0};
  config.geometry.t_w_mm = {5.0, -5.0, 100.0};
  const hal::Timestamp t0 = std::chrono::seconds(20);
  const double rate = config.geometry.sweep_rate_rad_s * 1e-9;  // rad/ns
  const double tilt = 0.1;
  const auto pan = [&](hal::Timestamp t) {
    return -0.4 + rate * static_cast<double>((t - t0).count());
  };
  PanTiltAssembler assembler(config);
  for (hal::Timestamp t = t0 - milliseconds(10); t <= t0 + milliseconds(10) * 101;
       t += milliseconds(10)) {
    assembler.add_pan_tilt({t - milliseconds(5), pan(t - milliseconds(5)), tilt, true});
  }
  const Plane plane{Eigen::Vector3d(0.1, 0.0, 1.0).normalized(), 1000.0};
  ProfileTruth truth;
  for (int p = 0; p < 100; ++p) {
    hal::RangerProfile profile;
    profile.sequence = static_cast<std::uint32_t>(1000 + p);
    profile.stamp = t0 + milliseconds(10) * p;
    std::vector<Eigen::Vector3d> hits;
    cast_profile(config.geometry.ranger, config.geometry.T_world_ranger(pan(profile.stamp), tilt),
                 plane, profile, hits);
    assembler.add_profile(profile);
    truth.profiles.push_back(std::move(profile));
    truth.hits.push_back(std::move(hits));
  }
  const FusedScan scan = assembler.finish();
  ASSERT_EQ(scan.cloud.grid.rows, 100);
  EXPECT_GT(scan.cloud.size(), 100u * 500u);
  EXPECT_LT(max_error(scan, truth), 0.001);
  EXPECT_EQ(scan.faults.total(), 0u);
}

TEST(PanTiltAssembler, EmptyScanGivesAnEmptyCloudWithoutFaults) {
  PanTiltAssembler assembler{PanTiltFusionConfig{}};
  EXPECT_TRUE(assembler.finish().cloud.empty());
}

TEST(PanTiltAssembler, ProfileWithoutAnyPoseSampleIsDroppedAndCounted) {
  PanTiltAssembler assembler{PanTiltFusionConfig{}};
  hal::RangerProfile profile;
  profile.x_mm = {0.0f};
  profile.z_mm = {500.0f};
  assembler.add_profile(profile);
  const FusedScan scan = assembler.finish();
  EXPECT_TRUE(scan.cloud.empty());
  EXPECT_EQ(scan.dropped_frames, 1u);
  EXPECT_EQ(scan.faults.extrapolated, 1u);
}

}  // namespace profile_assembler_test
}  // namespace rangefit::fusion
