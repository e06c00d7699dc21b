#pragma once
// The thesis's RSF statistics and timing (tables 4.1-4.4, 4.2.2-4.2.3) reproduced on the bore
// benchmark's scan, rangefit's figures beside the thesis's: bore_benchmark --thesis_tables=N
// (N trials per sample count; the thesis averaged 1,000). Thesis figures are those printed in
// its tables (a real 5 mm bore, 1,254 wall points; a 2005 PC); rangefit's are on the synthetic
// scan of bore_bench_scan.hpp (5 mm bore, 0.2 mm spacing) and one core of this machine.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>
#include <span>
#include <vector>

#include "detect/bore/bore_detector.hpp"
#include "detect/bore/cylinder_rsf.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit::bench {

inline double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

struct Spread {
  double mean = 0, sem = 0, max = 0, min = 0;  // sem: standard error of the mean
};

inline Spread spread(const std::vector<double>& v) {
  Spread s;
  if (v.empty()) return s;
  double ss = 0.0;
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.sem = std::sqrt(ss / static_cast<double>(v.size())) / std::sqrt(static_cast<double>(v.size()));
  s.max = *std::max_element(v.begin(), v.end());
  s.min = *std::min_element(v.begin(), v.end());
  return s;
}

inline double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) * 180.0 /
         std::numbers::pi;
}

// Tables 4.1 and 4.2: the RSF's pair axis u (eq. 4.7) and radius (eq. 4.15) against the number
// of samples, `trials` seeds each.
inline void thesis_tables_41_42(std::span<const Eigen::Vector3d> wall,
                                std::span<const Eigen::Vector3d> normals, const BorePrior& prior,
                                const sim::SyntheticBoreTruth& t, int trials) {
  std::printf("\nTables 4.1/4.2: RSF samples vs accuracy (%zu wall points, %d trials each)\n",
              wall.size(), trials);
  std::printf("%8s | %9s %9s %9s %9s | %9s %9s %9s %9s %9s\n", "samples", "|du| deg", "tau", "max",
              "min", "r mm", "dr", "tau", "max", "min");
  for (int n = 10; n <= 100000; n *= 10) {
    RsfOptions o;
    o.axis_samples = o.radius_samples = n;
    std::vector<double> du, r;
    for (int k = 0; k < trials; ++k) {
      const RsfResult x = fit_cylinder_rsf(wall, normals, prior.axis, prior.entrance, prior.radius,
                                           o, 1000 + static_cast<std::uint64_t>(k));
      if (x.status != RsfStatus::kOk) continue;
      du.push_back(angle_deg(x.axis_from_pairs, t.axis));
      r.push_back(x.cylinder.radius);
    }
    const Spread a = spread(du), b = spread(r);
    std::printf("%8d | %9.3f %9.4f %9.3f %9.3f | %9.3f %+9.3f %9.4f %9.3f %9.3f\n", n, a.mean,
                a.sem, a.max, a.min, b.mean, b.mean - t.radius, b.sem, b.max, b.min);
  }
  std::printf(
      "thesis 10^3: |du| 3.227 +-0.001 (3.711..2.791) deg; r 4.963 mm, dr -0.036, "
      "+-0.0025 (5.036..4.885)\n");
  std::printf(
      "thesis 10^5: |du| 3.229 +-0.0005 (3.282..3.182) deg; r 4.963 mm, dr -0.036, "
      "+-0.0 (4.973..4.955)\n");
}

// Least-squares circle of points projected along `axis`: algebraic (Kasa) start, then
// Gauss-Newton on the geometric distances (the thesis's LSF of 4.2.2). Returns the radius and
// its standard error (residual rms / sqrt(n)).
inline std::pair<double, double> lsf_circle(std::span<const Eigen::Vector3d> pts,
                                            const Eigen::Vector3d& axis) {
  const Eigen::Vector3d e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  std::vector<Eigen::Vector2d> q;
  for (const auto& p : pts) q.emplace_back(p.dot(e1), p.dot(e2));
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const auto& x : q) {
    const Eigen::Vector3d row(x.x(), x.y(), 1.0);
    a += row * row.transpose();
    b += row * x.squaredNorm();
  }
  const Eigen::Vector3d s = a.ldlt().solve(b);
  Eigen::Vector2d c(0.5 * s(0), 0.5 * s(1));
  double r = std::sqrt(std::max(s(2) + c.squaredNorm(), 0.0));
  double ss = 0.0;
  for (int it = 0; it < 20; ++it) {
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jtr = Eigen::Vector3d::Zero();
    ss = 0.0;
    for (const auto& x : q) {
      const Eigen::Vector2d d = x - c;
      const double n = d.norm();
      if (n < 1e-12) continue;
      const Eigen::Vector3d j(-d.x() / n, -d.y() / n, -1.0);
      const double res = n - r;
      jtj += j * j.transpose();
      jtr += j * res;
      ss += res * res;
    }
    const Eigen::Vector3d step = -jtj.ldlt().solve(jtr);
    c += step.head<2>();
    r += step(2);
    if (step.norm() < 1e-9) break;
  }
  const double n = static_cast<double>(q.size());
  return {r, std::sqrt(ss / n) / std::sqrt(n)};
}

// Table 4.3: RSF (10^3 samples) against the LSF circle on the wall at 100, 50, 25, 10, 4 %.
inline void thesis_table_43(std::span<const Eigen::Vector3d> wall,
                            std::span<const Eigen::Vector3d> normals, const BorePrior& prior,
                            int trials) {
  std::printf(
      "\nTable 4.3: RSF (10^3 samples) vs LSF circle per resolution (CPU ms; tau: RSF "
      "sd over %d seeds, LSF standard error)\n",
      trials);
  std::printf("%6s %6s | %9s %9s %10s %10s | thesis points t_LSF t_RSF tau_LSF tau_RSF\n", "share",
              "points", "t_LSF", "t_RSF", "tau_LSF", "tau_RSF");
  const char* thesis[] = {"1254 228.4 2.09 0.0005 0.023", "631 116.1 2.09 0.018 0.023",
                          "313 58.7 2.16 0.022 0.023", "124 24.6 2.25 0.031 0.023",
                          "50 11.2 2.56 0.062 0.023"};
  const int share[] = {100, 50, 25, 10, 4};
  for (int s = 0; s < 5; ++s) {
    std::vector<Eigen::Vector3d> p, n;
    const double keep = share[s] / 100.0;
    double acc = 0.0;
    for (std::size_t i = 0; i < wall.size(); ++i) {
      acc += keep;
      if (acc >= 1.0) acc -= 1.0, p.push_back(wall[i]), n.push_back(normals[i]);
    }
    std::vector<double> r;
    double t_rsf = 0.0;
    Eigen::Vector3d axis = prior.axis;
    for (int k = 0; k < trials; ++k) {
      const double t0 = thread_cpu_ms();
      const RsfResult x = fit_cylinder_rsf(p, n, prior.axis, prior.entrance, prior.radius, {},
                                           1000 + static_cast<std::uint64_t>(k));
      t_rsf += thread_cpu_ms() - t0;
      if (x.status == RsfStatus::kOk) r.push_back(x.cylinder.radius), axis = x.cylinder.axis;
    }
    const double t0 = thread_cpu_ms();
    std::pair<double, double> lsf{};
    for (int k = 0; k < trials; ++k) lsf = lsf_circle(p, axis);
    const double t_lsf = (thread_cpu_ms() - t0) / trials;
    std::printf("%5d%% %6zu | %9.3f %9.3f %10.4f %10.4f | %s\n", share[s], p.size(), t_lsf,
                t_rsf / trials, lsf.second, spread(r).sem * std::sqrt(double(r.size())), thesis[s]);
  }
}

// Table 4.4 / fig. 4.27: the whole pipeline per normal resolution (the thesis's sub-sampling,
// normal_keep) on a 5 and a 10 mm bore, session 1's pipeline (every region point gets a normal
// at R = 2 mm, as the thesis) and the default, with the time per stage.
inline void thesis_table_44(int runs) {
  std::printf(
      "\nTable 4.4: time per resolution (median CPU ms of %d runs, -: not found; wall ms of the "
      "default's last run: roi / normals / segmentation / rsf / refine)\n",
      runs);
  std::printf("%4s %4s %7s %6s %7s %9s %9s | %-36s | thesis\n", "bore", "keep", "scan", "roi",
              "queries", "session 1", "default", "default stages");
  const char* thesis[2][5] = {
      {"7481 pts 1386 ms", "3740 723", "1870 418", "748 235", "299 418"},
      {"45688 pts 16626 ms", "24344 7797", "12172 4016", "4569 1641", "1827 767"}};
  const int keep[] = {100, 50, 25, 10, 4};
  for (int b = 0; b < 2; ++b) {
    sim::SyntheticBoreOptions so;
    so.radius = b == 0 ? 5.0 : 10.0;
    so.extent = 27.4;
    so.spacing = 0.2;
    so.seed = 7;
    const sim::SyntheticBoreScan scan = sim::make_synthetic_bore(so);
    BorePrior prior;
    prior.entrance = scan.truth.entrance + Eigen::Vector3d(0.3, -0.2, 0.1);
    prior.axis = (scan.truth.axis + Eigen::Vector3d(0.03, 0.0, 0.0)).normalized();
    prior.radius = so.radius;
    prior.plane_normal = scan.truth.plane_normal;
    for (int k = 0; k < 5; ++k) {
      double med[2];
      BoreResult r[2];
      for (int mode = 0; mode < 2; ++mode) {
        BoreOptions o;
        o.view_dir = scan.truth.view_dir;
        o.normal_keep = keep[k] / 100.0;
        o.cost_bounded = mode == 1;
        std::vector<double> t;
        for (int i = 0; i < runs; ++i) {
          const double t0 = thread_cpu_ms();
          r[mode] = detect_bore(scan.cloud, prior, o);
          t.push_back(thread_cpu_ms() - t0);
        }
        std::sort(t.begin(), t.end());
        med[mode] = t[t.size() / 2];
      }
      const BoreTimes& s = r[1].time_ms;
      char stages[64];
      std::snprintf(stages, sizeof stages, "%.3f %.3f %.3f %.3f %.3f", s.roi, s.normals,
                    s.segmentation, s.rsf, s.refine);
      std::printf("%4.0f %3d%% %7zu %6zu %7zu %8.2f%c %8.3f%c | %-36s | %s\n", 2 * so.radius,
                  keep[k], scan.cloud.size(), r[0].counts.roi, r[0].counts.normal_queries, med[0],
                  r[0].found ? ' ' : '-', med[1], r[1].found ? ' ' : '-', stages, thesis[b][k]);
    }
  }
}

}  // namespace rangefit::bench
