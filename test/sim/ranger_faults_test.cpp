// Seeded faults of the stripe cell and the pan-tilt head: the streams
// report them as a real device does (sequence gaps, health counters and state, repeated
// readings, jittered stamps), and fusion's assemblers see them exactly so.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fusion/profile_assembler.hpp"
#include "sim/pan_tilt_head.hpp"
#include "sim/sim_clock.hpp"
#include "sim/stripe_cell.hpp"

namespace rangefit::sim {
namespace ranger_faults_test {

using std::chrono::milliseconds;

// A table with a ball on it, under the stripe cell and under the pan-tilt head (800 mm up).
Scene ball_scene() {
  Scene s;
  s.objects.push_back({"table", PlaneShape{500.0, 500.0}, Eigen::Isometry3d::Identity()});
  Eigen::Isometry3d ball = Eigen::Isometry3d::Identity();
  ball.translation() = Eigen::Vector3d(0.0, 180.0, 40.0);
  s.objects.push_back({"ball", SphereShape{40.0}, ball});
  s.mounts.T_scene_pantilt.linear() =
      Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  s.mounts.T_scene_pantilt.translation() = Eigen::Vector3d(0.0, 150.0, 800.0);
  return s;
}

// What a consumer got from one scan: both streams, the fused scan and what the devices said.
template <class Pose>
struct Recorded {
  std::vector<hal::RangerProfile> profiles;
  std::vector<Pose> poses;
  fusion::FusedScan scan;
  hal::DeviceHealth ranger, motion;
  bool ranger_lost = false, motion_lost = false;  // seen disconnected mid-scan
};

// Reads both streams in slices until `running` is false, feeding the assembler as they arrive.
template <class Pose, class Assembler, class AddPose>
Recorded<Pose> record(hal::RangerSource& ranger, hal::SampleSource<Pose>& motion,
                      Assembler& assembler, AddPose add_pose,
                      const std::function<bool()>& running) {
  Recorded<Pose> r;
  assembler.begin_scan();
  EXPECT_TRUE(ranger.start());
  EXPECT_TRUE(motion.start());
  while (running()) {
    const std::size_t p0 = r.profiles.size(), s0 = r.poses.size();
    motion.read(r.poses, milliseconds(50));
    ranger.read(r.profiles, milliseconds(0));
    for (std::size_t i = s0; i < r.poses.size(); ++i) add_pose(assembler, r.poses[i]);
    for (std::size_t i = p0; i < r.profiles.size(); ++i) assembler.add_profile(r.profiles[i]);
    r.ranger_lost |= ranger.health().state == hal::DeviceState::kDisconnected;
    r.motion_lost |= motion.health().state == hal::DeviceState::kDisconnected;
  }
  r.scan = assembler.finish();
  r.ranger = ranger.health();
  r.motion = motion.health();
  return r;
}

Recorded<hal::AxisSample> stripe_scan(const StripeCellOptions& o, double travel_mm) {
  const Scene scene = ball_scene();
  const RayCaster caster(scene);
  SimClock clock;
  StripeCell cell(scene, caster, o, clock);
  fusion::StripeCellFusionConfig config;
  config.geometry = o.geometry;
  config.limits.max_faults = 1000;  // count, do not judge
  fusion::StripeCellAssembler assembler(config);
  EXPECT_TRUE(cell.axis().enable());
  EXPECT_TRUE(cell.axis().move_to(travel_mm, o.geometry.max_speed_mm_s));
  return record(
      cell.ranger(), cell.axis(), assembler,
      [](fusion::StripeCellAssembler& a, const hal::AxisSample& s) { a.add_axis(s); },
      [&] { return !cell.axis().motion_complete(); });
}

Recorded<hal::PanTiltSample> pan_tilt_scan(const PanTiltOptions& o) {
  const Scene scene = ball_scene();
  const RayCaster caster(scene);
  SimClock clock;
  PanTiltHead head(scene, caster, o, clock);
  fusion::PanTiltFusionConfig config;
  config.geometry = o.geometry;
  config.limits.max_faults = 1000;
  fusion::PanTiltAssembler assembler(config);
  return record(
      head.ranger(), head.angles(), assembler,
      [](fusion::PanTiltAssembler& a, const hal::PanTiltSample& s) { a.add_pan_tilt(s); },
      [&] { return clock.now() < head.sweep_end(); });
}

// Frames lost between delivered ones, and the number of places they were lost at.
std::pair<std::uint64_t, std::uint32_t> sequence_gaps(const std::vector<hal::RangerProfile>& ps) {
  std::uint64_t missing = 0;
  std::uint32_t places = 0;
  for (std::size_t i = 1; i < ps.size(); ++i) {
    const std::uint32_t step = ps[i].sequence - ps[i - 1].sequence;
    missing += step - 1;
    places += step > 1 ? 1 : 0;
  }
  return {missing, places};
}

TEST(RangerFaults, CleanScansHaveNoGapsAndNoFaults) {
  const auto s = stripe_scan(StripeCellOptions{}, 30.0);
  const auto p = pan_tilt_scan(PanTiltOptions{});
  for (const auto* scan : {&s.scan, &p.scan}) {
    EXPECT_EQ(scan->faults.total(), 0u);
    EXPECT_FALSE(scan->bad);
  }
  EXPECT_EQ(sequence_gaps(s.profiles).first, 0u);
  EXPECT_EQ(sequence_gaps(p.profiles).first, 0u);
  EXPECT_EQ(s.scan.cloud.grid.rows, static_cast<int>(s.profiles.size()));
  EXPECT_GT(p.scan.cloud.grid.rows, 400);  // 5 s at 100 profiles/s
}

TEST(RangerFaults, DroppedProfilesAreSequenceGapsCountedByDeviceAndFusion) {
  StripeCellOptions so;
  so.seed = 3;
  so.ranger_faults.drop_probability = 0.1;
  PanTiltOptions po;
  po.seed = 3;
  po.ranger_faults.drop_probability = 0.1;
  const auto s = stripe_scan(so, 40.0);
  const auto p = pan_tilt_scan(po);
  for (const auto* r : {&s.profiles, &p.profiles}) ASSERT_GT(r->size(), 50u);
  const auto [s_missing, s_places] = sequence_gaps(s.profiles);
  const auto [p_missing, p_places] = sequence_gaps(p.profiles);
  EXPECT_GT(s_missing, 0u);
  EXPECT_GT(p_missing, 20u);
  EXPECT_EQ(s.ranger.counters.gaps, s_missing);
  EXPECT_EQ(p.ranger.counters.gaps, p_missing);
  EXPECT_EQ(s.ranger.counters.samples, s.profiles.size());
  EXPECT_NE(p.ranger.message.find("frame lost"), std::string::npos) << p.ranger.message;
  // Fusion counts one gap per place frames were lost and fuses every profile it got.
  EXPECT_EQ(s.scan.faults.gaps, s_places);
  EXPECT_EQ(p.scan.faults.gaps, p_places);
  EXPECT_EQ(p.scan.cloud.grid.rows, static_cast<int>(p.profiles.size()));
  EXPECT_EQ(p.scan.faults.clock_jumps, 0u) << "a lost profile is not a clock jump";
}

TEST(RangerFaults, ProfileStampJitterBeyondTheToleranceShowsAsClockJumps) {
  PanTiltOptions calm, shaky;
  calm.ranger_faults.stamp_jitter_sigma = std::chrono::microseconds(100);
  shaky.ranger_faults.stamp_jitter_sigma = milliseconds(3);  // tolerance: 2 ms
  calm.seed = shaky.seed = 9;
  const auto a = pan_tilt_scan(calm);
  const auto b = pan_tilt_scan(shaky);
  EXPECT_EQ(a.scan.faults.clock_jumps, 0u);
  EXPECT_GT(b.scan.faults.clock_jumps, 100u);
  std::size_t off_grid = 0;  // stamps are no longer on the 10 ms grid
  for (std::size_t i = 1; i < b.profiles.size(); ++i) {
    off_grid += b.profiles[i].stamp - b.profiles[i - 1].stamp != milliseconds(10) ? 1 : 0;
  }
  EXPECT_GT(off_grid, b.profiles.size() / 2);
}

TEST(RangerFaults, AngleStampJitterReordersSamplesAndFusionDropsThem) {
  PanTiltOptions o;
  o.seed = 4;
  o.angle_faults.stamp_jitter_sigma = milliseconds(8);  // samples are 10 ms apart
  const auto r = pan_tilt_scan(o);
  // A real consumer keeps a sample only when it is later than the last one it kept.
  std::uint32_t backwards = 0;
  hal::Timestamp last = r.poses.front().stamp;
  for (std::size_t i = 1; i < r.poses.size(); ++i) {
    if (r.poses[i].stamp <= last) {
      ++backwards;
    } else {
      last = r.poses[i].stamp;
    }
  }
  EXPECT_GT(backwards, 10u);
  EXPECT_EQ(r.scan.faults.out_of_order, backwards);
}

TEST(RangerFaults, StaleAxisReadingsRepeatThePositionWithAFreshStamp) {
  StripeCellOptions o;
  o.seed = 6;
  o.axis_faults.stale_probability = 0.3;
  const auto r = stripe_scan(o, 30.0);
  std::size_t moving = 0, repeated = 0;
  for (std::size_t i = 1; i < r.poses.size(); ++i) {
    if (r.poses[i].velocity_mm_s <= 0.0 || r.poses[i - 1].velocity_mm_s <= 0.0) continue;
    ++moving;
    ASSERT_GT(r.poses[i].stamp, r.poses[i - 1].stamp);
    repeated += r.poses[i].position_mm == r.poses[i - 1].position_mm ? 1 : 0;
  }
  ASSERT_GT(moving, 200u);
  // 6.3 mm/s polled at 50 Hz moves 0.126 mm (> 2 counts of 0.05 mm) between polls.
  EXPECT_NEAR(static_cast<double>(repeated) / static_cast<double>(moving), 0.3, 0.08);
  // Nothing in the streams' timing betrays a stale reading: fusion counts no fault.
  EXPECT_EQ(r.scan.faults.total(), 0u);
}

TEST(RangerFaults, StalePanAnglesRepeatTheAngleWithAFreshStamp) {
  PanTiltOptions o;
  o.seed = 6;
  o.angle_faults.stale_probability = 0.2;
  const auto r = pan_tilt_scan(o);
  std::size_t repeated = 0;
  for (std::size_t i = 1; i < r.poses.size(); ++i) {
    repeated += r.poses[i].pan_rad == r.poses[i - 1].pan_rad ? 1 : 0;
  }
  ASSERT_GT(r.poses.size(), 400u);
  EXPECT_NEAR(static_cast<double>(repeated) / static_cast<double>(r.poses.size()), 0.2, 0.06);
  EXPECT_EQ(r.scan.faults.total(), 0u);
}

TEST(RangerFaults, AxisDisconnectMidScanIsReportedAndRecovered) {
  StripeCellOptions o;
  o.axis_faults.disconnect_after = milliseconds(2000);
  o.axis_faults.disconnect_for = milliseconds(500);
  const auto r = stripe_scan(o, 30.0);
  EXPECT_TRUE(r.motion_lost);
  EXPECT_FALSE(r.ranger_lost);
  EXPECT_EQ(r.motion.state, hal::DeviceState::kStreaming);
  EXPECT_EQ(r.motion.counters.reconnects, 1u);
  EXPECT_NEAR(static_cast<double>(r.motion.counters.gaps), 25.0, 1.0);  // 0.5 s at 50 Hz
  EXPECT_NE(r.motion.message.find("link lost"), std::string::npos) << r.motion.message;
  // Fusion sees half a second without positions: one reference gap.
  EXPECT_EQ(r.scan.faults.gaps, 1u);
}

TEST(RangerFaults, RangerAndPanTiltDisconnectsMidSweepAreReportedAndRecovered) {
  PanTiltOptions a, b;
  a.ranger_faults.disconnect_after = b.angle_faults.disconnect_after = milliseconds(1500);
  a.ranger_faults.disconnect_for = b.angle_faults.disconnect_for = milliseconds(300);
  const auto lost_ranger = pan_tilt_scan(a);
  const auto lost_angles = pan_tilt_scan(b);
  EXPECT_TRUE(lost_ranger.ranger_lost);
  EXPECT_TRUE(lost_angles.motion_lost);
  for (const auto* h : {&lost_ranger.ranger, &lost_angles.motion}) {
    EXPECT_EQ(h->state, hal::DeviceState::kStreaming);
    EXPECT_EQ(h->counters.reconnects, 1u);
    EXPECT_NEAR(static_cast<double>(h->counters.gaps), 30.0, 1.0);  // 0.3 s at 100 Hz
  }
  EXPECT_EQ(sequence_gaps(lost_ranger.profiles).second, 1u);
  EXPECT_EQ(lost_ranger.scan.faults.gaps, 1u) << "the missing profiles";
  EXPECT_EQ(lost_angles.scan.faults.gaps, 1u) << "the missing angles";
}

}  // namespace ranger_faults_test
}  // namespace rangefit::sim
