// The service calibrates from the fused scan, not the raw stream: what it takes back must be what
// the devices reported. A CSS scan and a pan-tilt sweep are fused by the real assemblers from
// known streams; the samples and profiles the calibration requests recover must be those.
#include <gtest/gtest.h>

#include <cmath>

#include "daemon/service/calibrate_css_request.hpp"
#include "daemon/service/calibrate_pan_tilt_request.hpp"
#include "detect/common/angles.hpp"
#include "fusion/css_assembler.hpp"
#include "fusion/profile_assembler.hpp"

namespace rangefit::daemon {
namespace calibration_raw_test {

using std::chrono::milliseconds;
using std::chrono::nanoseconds;

TEST(CalibrationRaw, TheCssSamplesComeBackFromTheFusedScan) {
  fusion::CssFusionConfig fc;
  fc.omega_zero_rad = 0.01;
  const double rate = 0.06;  // rad/s
  const hal::Timestamp t0 = milliseconds(1000);
  std::vector<hal::JointSample> joints;
  for (int k = 0; k <= 1000; ++k) {  // 250 Hz for 4 s
    hal::JointSample j;
    j.joint = fc.joint;
    j.stamp = t0 + milliseconds(4 * k);
    j.angle_rad = fc.omega_zero_rad - 0.1 + rate * 0.004 * k;
    joints.push_back(j);
  }
  std::vector<hal::CssRevolution> revs;
  const nanoseconds period(1'000'000'000 / 7);
  for (int r = 0; r < 20; ++r) {
    hal::CssRevolution rev;
    rev.sequence = static_cast<std::uint32_t>(r);
    rev.stamp = t0 + milliseconds(100) + r * period;
    rev.period = period;
    for (int i = 0; i < hal::CssRevolution::kSamples; ++i) {
      rev.range_mm[i] =
          i % 7 == 3 ? std::nanf("") : static_cast<float>(90.0 + 20.0 * std::sin(0.05 * i + r));
    }
    revs.push_back(rev);
  }
  const fusion::FusedScan fused = fusion::fuse_css_scan(fc, revs, joints);
  ASSERT_FALSE(fused.bad) << fused.reason;
  const CssRawSamples raw = css_raw_samples(fused.cloud, {fc.geometry, fc.omega_zero_rad});
  ASSERT_EQ(raw.error, "");
  ASSERT_EQ(raw.samples.size(), fused.cloud.points.size());
  std::size_t k = 0;
  double worst_omega = 0.0, worst_range = 0.0;
  for (const auto& rev : revs) {
    for (int i = 0; i < hal::CssRevolution::kSamples; ++i) {
      if (!std::isfinite(rev.range_mm[i])) continue;
      ASSERT_LT(k, raw.samples.size());
      const calib::CssSample& s = raw.samples[k++];
      const double t =
          static_cast<double>((rev.stamp - t0).count()) * 1e-9 +
          static_cast<double>(period.count()) * 1e-9 * i / hal::CssRevolution::kSamples;
      worst_omega =
          std::max(worst_omega, std::abs(s.omega_rad - (fc.omega_zero_rad - 0.1 + rate * t)));
      worst_range = std::max(worst_range, std::abs(s.range_mm - rev.range_mm[i]));
      EXPECT_DOUBLE_EQ(s.beam_rad, fc.geometry.beam_angle(i, hal::CssRevolution::kSamples));
    }
  }
  EXPECT_EQ(k, raw.samples.size());
  EXPECT_LT(worst_omega, 1e-9);
  EXPECT_LT(worst_range, 1e-6);
}

// A head sweep fused from a pan stream at a held tilt, and the sensor the scan reports.
struct FusedSweep {
  fusion::FusedScan fused;
  ScanSensor sensor;
  std::vector<hal::RangerProfile> profiles;
};

FusedSweep head_sweep(double tilt_rad) {
  fusion::PanTiltFusionConfig fc;
  fc.geometry.t_s_mm = {1.0, -2.0, 30.0};
  fc.geometry.t_w_mm = {5.0, 3.0, -4.0};
  FusedSweep out;
  fusion::PanTiltAssembler assembler(fc);
  assembler.begin_scan();
  const hal::Timestamp t0 = milliseconds(500);
  for (int k = 0; k <= 300; ++k) {  // 100 Hz, 0.2 rad/s
    hal::PanTiltSample a;
    a.stamp = t0 + milliseconds(10 * k);
    a.pan_rad = -0.3 + 0.002 * k;
    a.tilt_rad = tilt_rad;
    assembler.add_pan_tilt(a);
  }
  for (int r = 0; r < 100; ++r) {
    hal::RangerProfile p;
    p.sequence = static_cast<std::uint32_t>(r);
    p.stamp = t0 + milliseconds(10 * r + 3);  // the configured 100 profiles/s
    for (int c = 0; c < 512; ++c) {
      p.x_mm.push_back(static_cast<float>(-100.0 + 0.4 * c));
      p.z_mm.push_back(c % 11 == 5 ? std::nanf("")
                                   : static_cast<float>(700.0 + 30.0 * std::cos(0.01 * c + r)));
    }
    assembler.add_profile(p);
    out.profiles.push_back(std::move(p));
  }
  out.fused = assembler.finish();
  out.sensor = pan_tilt_sensor(fc.geometry, 0.3, tilt_rad);
  for (const auto& f : out.fused.frames) out.sensor.row_poses.push_back(f.pose);
  return out;
}

TEST(CalibrationRaw, ThePanTiltProfilesAndAnglesComeBackFromTheFusedScan) {
  const FusedSweep s = head_sweep(0.1);
  ASSERT_FALSE(s.fused.bad) << s.fused.reason;
  const RawPanTiltSweep raw = raw_pan_tilt_sweep(s.fused.cloud, s.sensor);
  ASSERT_EQ(raw.error, "");
  ASSERT_EQ(raw.sweep.profiles.size(), s.profiles.size());
  double worst = 0.0;
  for (std::size_t r = 0; r < s.profiles.size(); ++r) {
    const double t = (10.0 * static_cast<double>(r) + 3.0) * 1e-3;
    EXPECT_NEAR(raw.sweep.angles[r].pan_rad, -0.3 + 0.2 * t, 1e-12);
    EXPECT_EQ(raw.sweep.angles[r].tilt_rad, 0.1);
    for (std::size_t c = 0; c < 512; ++c) {
      const float z = s.profiles[r].z_mm[c];
      ASSERT_EQ(std::isfinite(z), std::isfinite(raw.sweep.profiles[r].z_mm[c])) << r << " " << c;
      if (!std::isfinite(z)) continue;
      worst = std::max(worst, static_cast<double>(
                                  std::abs(raw.sweep.profiles[r].x_mm[c] - s.profiles[r].x_mm[c])));
      worst = std::max(worst, static_cast<double>(std::abs(raw.sweep.profiles[r].z_mm[c] - z)));
    }
  }
  EXPECT_LT(worst, 1e-4);  // float profiles
}

TEST(CalibrationRaw, ASweepAtAnotherTiltThanTheRequestSaysIsAnError) {
  const FusedSweep s = head_sweep(0.1);
  ScanRequest req;
  req.id = "tilt-check";
  req.kind = DetectKind::kCalibrate;
  req.target.kind = "pantilt";
  req.target.tilt_rad = 0.05;
  PanTiltCalibrationSweeps sweeps;
  const DetectionResult r = calibrate_pan_tilt_request(s.fused.cloud, req, s.sensor, sweeps, 1);
  EXPECT_FALSE(r.found);
  EXPECT_NE(r.reason.find("did not hold the tilt"), std::string::npos) << r.reason;
  req.target.tilt_rad = 0.1;  // as reported: recorded, one tilt of two
  const DetectionResult ok = calibrate_pan_tilt_request(s.fused.cloud, req, s.sensor, sweeps, 1);
  EXPECT_NE(ok.reason.find("1 of at least 2 tilts"), std::string::npos) << ok.reason;
  EXPECT_NE(sweeps.find("tilt-check"), nullptr);
}

}  // namespace calibration_raw_test
}  // namespace rangefit::daemon
