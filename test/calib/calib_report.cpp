// Spread over many seeds against the reported covariance (what the tests check with few seeds):
//   build/test/calib/calib_report [SEEDS] [stripe|rig|css|pantilt|all] [quantised]
//                                                                         (default 20 all)
// Per calibration and parameter: the rms error over the seeds, the mean reported 1 sigma and
// their ratio (1: the covariance is right; the goal is within a factor of 1.5), all at 0.06 mm
// noise. `quantised`: the stripe cell's and the head's depths also rounded to the chip's rows
// as the real ranger (and the daemon's simulated one) does; the cell is then drawn anew per seed.
// `rig`: two cameras of one laser plane, one on each side (calib_fixtures.hpp Rig), calibrated
// together and each on its own: their rms errors side by side, and the joint covariance.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "calib/stripe_calibration.hpp"
#include "calib_fixtures.hpp"
#include "css_fixtures.hpp"
#include "pan_tilt_fixtures.hpp"
#include "sim/calibration_scans.hpp"

using namespace rangefit;
using namespace rangefit::test;

namespace {

// Errors and reported sigmas of one parameter over the seeds.
struct Spread {
  const char* name;
  double scale;  // to the printed unit
  double err2 = 0.0, sigma = 0.0;
};

void print(const char* title, int n, std::vector<Spread>& s) {
  std::printf("%s, 0.06 mm noise, %d seeds\n", title, n);
  double worst = 1.0;
  for (Spread& p : s) {
    const double rms = std::sqrt(p.err2 / n) * p.scale, sigma = p.sigma / n * p.scale;
    const double ratio = rms / sigma;
    worst = std::max({worst, ratio, 1.0 / ratio});
    std::printf("  %-14s rms error %.5f  reported sigma %.5f  ratio %.2f\n", p.name, rms, sigma,
                ratio);
  }
  std::printf("  worst factor %.2f (goal <= 1.5)\n", worst);
}

void stripe(int seeds, bool quantise) {
  const hal::StripeCellGeometry nominal;
  std::vector<Spread> s = {{"x mm", 1.0},        {"y mm", 1.0},        {"z mm", 1.0},
                           {"rx deg", 1 / kDeg}, {"ry deg", 1 / kDeg}, {"rz deg", 1 / kDeg}};
  int n = 0;
  for (int k = 0; k < seeds; ++k) {
    // Quantised depths are a fixed function of the geometry: the cell is drawn anew per seed so
    // that their errors vary over the seeds.
    const hal::StripeCellGeometry truth =
        perturbed_cell(nominal, quantise ? 500u + static_cast<unsigned>(k) : 7u);
    const auto r = calibrate(stripe_cube_sweep(truth, {.sigma_mm = 0.06,
                                                       .quantise = quantise,
                                                       .seed = 100000u + static_cast<unsigned>(k)}),
                             nominal);
    if (!r.ok) {
      std::printf("stripe seed %d: %s\n", k, r.reason.c_str());
      continue;
    }
    const Eigen::Vector3d dp = r.geometry.ranger_position_cell_mm - truth.ranger_position_cell_mm;
    const Eigen::AngleAxisd w(truth.T_cell_ranger().linear().transpose() *
                              r.geometry.T_cell_ranger().linear());
    const Eigen::Vector3d dw = w.angle() * w.axis();
    for (int i = 0; i < 3; ++i) {
      s[i].err2 += dp[i] * dp[i];
      s[3 + i].err2 += dw[i] * dw[i];
      s[i].sigma += r.position_sigma_mm[i];
      s[3 + i].sigma += r.rotation_sigma_rad[i];
    }
    ++n;
  }
  print(quantise ? "stripe cell, 1 mm profiles, depths quantised" : "stripe cell, 1 mm profiles", n,
        s);
}

void rig(int seeds) {
  // Per camera: position (mm) and rotation (deg) errors, together and alone.
  double joint_p = 0.0, joint_r = 0.0, alone_p = 0.0, alone_r = 0.0;
  NormalisedErrors e;
  int n = 0;
  for (int k = 0; k < seeds; ++k) {
    const auto seed = static_cast<std::uint64_t>(500 + k);
    const Rig r = two_sided_rig(seed, {.sigma_mm = 0.06, .seed = 100000u + seed});
    const calib::StripeRigResult joint = calibrate_rig(r.a, r.b);
    calib::StripeCalibrationInput in;
    in.T_table_cube = cube_between_cameras();
    in.profiles = r.b.profiles;
    in.axis_mm = r.b.axis;
    const auto alone_b = calib::calibrate_stripe_cell(
        in, other_side_camera(hal::StripeCellGeometry{}, Eigen::Isometry3d::Identity()));
    in.profiles = r.a.profiles;
    in.axis_mm = r.a.axis;
    const auto alone_a = calib::calibrate_stripe_cell(in, hal::StripeCellGeometry{});
    if (!joint.ok || !alone_a.ok || !alone_b.ok) {
      std::printf("rig seed %d: %s%s%s\n", k, joint.reason.c_str(), alone_a.reason.c_str(),
                  alone_b.reason.c_str());
      continue;
    }
    for (std::size_t c = 0; c < 2; ++c) {
      const hal::StripeCellGeometry& t = c == 0 ? r.truth_a : r.truth_b;
      const auto& j = joint.cameras[c];
      const auto& a = c == 0 ? alone_a : alone_b;
      joint_p += (j.geometry.ranger_position_cell_mm - t.ranger_position_cell_mm).squaredNorm();
      alone_p += (a.geometry.ranger_position_cell_mm - t.ranger_position_cell_mm).squaredNorm();
      joint_r += std::pow(
          angle_between(j.geometry.T_cell_ranger().linear(), t.T_cell_ranger().linear()), 2);
      alone_r += std::pow(
          angle_between(a.geometry.T_cell_ranger().linear(), t.T_cell_ranger().linear()), 2);
      e.add(j, t);
    }
    n += 2;
  }
  std::printf("two cameras on both sides of one laser plane, 0.06 mm noise, %d seeds\n", n / 2);
  std::printf("  per camera rms position error: together %.4f mm, each alone %.4f mm\n",
              std::sqrt(joint_p / n), std::sqrt(alone_p / n));
  std::printf("  per camera rms rotation error: together %.5f deg, each alone %.5f deg\n",
              std::sqrt(joint_r / n) / kDeg, std::sqrt(alone_r / n) / kDeg);
  std::printf("  together: mean squared error / reported variance %.2f (goal 1/2.25 .. 2.25)\n",
              e.mean());
}

void css(int seeds) {
  const hal::CssGeometry g;
  const CssMountTruth truth = perturbed_mount(g, 3);
  std::vector<Spread> s = {{"omega_zero deg", 1 / kDeg}, {"mount y mm", 1.0},
                           {"mount z mm", 1.0},          {"mount rx deg", 1 / kDeg},
                           {"mount ry deg", 1 / kDeg},   {"mount rz deg", 1 / kDeg}};
  Spread axis{"bore axis deg", 1 / kDeg};
  int n = 0;
  for (int k = 0; k < seeds; ++k) {
    const auto r = calib::calibrate_css_mount(
        css_sphere_scans(g, truth, 0.06, 200000u + static_cast<unsigned>(k), 7), g, 0.0,
        {.sphere_radius_mm = kRadius});
    if (!r.ok) {
      std::printf("css seed %d: %s\n", k, r.reason.c_str());
      continue;
    }
    const Eigen::AngleAxisd w(truth.mount.linear().transpose() * r.T_joint_css.linear());
    const Eigen::Vector3d dw = w.angle() * w.axis();
    const Eigen::Vector3d dt = r.T_joint_css.translation() - truth.mount.translation();
    const double e[6] = {
        r.omega_zero_rad - truth.omega_zero, dt.y(), dt.z(), dw.x(), dw.y(), dw.z()};
    for (int i = 0; i < 6; ++i) {
      s[i].err2 += e[i] * e[i];
      s[i].sigma += std::sqrt(r.covariance(i, i));
    }
    // The predicted bore-axis error against the true one: the sensor's z-axis at omega = 0.
    const auto z_at_zero = [](const Eigen::Matrix3d& R, double zero) {
      return Eigen::Vector3d(Eigen::AngleAxisd(-zero, Eigen::Vector3d::UnitY()) * R.col(2));
    };
    const double da =
        std::acos(std::min(1.0, z_at_zero(r.T_joint_css.linear(), r.omega_zero_rad)
                                    .dot(z_at_zero(truth.mount.linear(), truth.omega_zero))));
    axis.err2 += da * da;
    axis.sigma += r.axis_sigma_rad;
    ++n;
  }
  s.push_back(axis);
  print("CSS mount, 8 sphere scans of 7 revolutions", n, s);
}

void pan_tilt(int seeds, bool quantise) {
  const hal::PanTiltGeometry nominal = configured_head();
  std::vector<Spread> s = {{"t_s x mm", 1.0},          {"t_s y mm", 1.0},
                           {"t_s z mm", 1.0},          {"t_w x mm", 1.0},
                           {"t_w y mm", 1.0},          {"t_w z mm", 1.0},
                           {"pan zero deg", 1 / kDeg}, {"tilt zero deg", 1 / kDeg}};
  int n = 0;
  for (int k = 0; k < seeds; ++k) {
    const hal::PanTiltGeometry truth =
        perturbed_head(nominal, quantise ? 500u + static_cast<unsigned>(k) : 7u);
    const auto r =
        run_pan_tilt(pan_tilt_sweeps(truth, 0.06, 300000u + 10u * static_cast<unsigned>(k),
                                     {-6.0, 0.0, 6.0}, 0.2, quantise),
                     nominal);
    if (!r.ok) {
      std::printf("pan-tilt seed %d: %s\n", k, r.reason.c_str());
      continue;
    }
    Eigen::Matrix<double, 8, 1> e;
    e << r.geometry.t_s_mm - truth.t_s_mm, r.geometry.t_w_mm - truth.t_w_mm,
        r.geometry.pan_zero_rad - truth.pan_zero_rad,
        r.geometry.tilt_zero_rad - truth.tilt_zero_rad;
    for (int i = 0; i < 8; ++i) {
      s[i].err2 += e[i] * e[i];
      s[i].sigma += std::sqrt(r.covariance(i, i));
    }
    ++n;
  }
  print(quantise ? "pan-tilt head, 3 sweeps at tilt -6/0/6 deg, depths quantised"
                 : "pan-tilt head, 3 sweeps at tilt -6/0/6 deg",
        n, s);
}

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 20;
  const std::string which = argc > 2 ? argv[2] : "all";
  if (seeds < 2 || (which != "all" && which != "stripe" && which != "rig" && which != "css" &&
                    which != "pantilt")) {
    std::fprintf(stderr,
                 "usage: calib_report [SEEDS >= 2] [stripe|rig|css|pantilt|all] [quantised]\n");
    return 1;
  }
  const bool quantise = argc > 3 && std::string(argv[3]) == "quantised";
  if (which == "all" || which == "stripe") stripe(seeds, quantise);
  if (which == "all" || which == "rig") rig(seeds);
  if (which == "all" || which == "css") css(seeds);
  if (which == "all" || which == "pantilt") pan_tilt(seeds, quantise);
  return 0;
}
