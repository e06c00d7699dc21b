#include "sim/scene_objects.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace rangefit::sim {
namespace {

struct Draw {
  std::mt19937_64& rng_;
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  std::mt19937_64& rng() { return rng_; }
};

Eigen::Isometry3d pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

}  // namespace

Eigen::Isometry3d pose_from_axis(const Eigen::Vector3d& centre, const Eigen::Vector3d& z,
                                 double spin_rad) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), z.normalized()) *
                Eigen::AngleAxisd(spin_rad, Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  T.translation() = centre;
  return T;
}

ObjectModel single(const std::string& name, const Superquadric& sq) {
  return ObjectModel{name, {ModelPart{name, sq}}, {}};
}

// Figure 5.18, table 5.3 poses.
std::vector<ScenePart> fig_5_18_parts() {
  return {{"cylinder", cylinder_model(),
           pose_from_axis({153.646, 146.348, 58.275}, {-0.35028, -0.33886, 0.87319})},
          {"box", box_model(),
           pose_from_axis({88.923, 94.128, 59.173}, {0.18692, -0.29300, 0.93767}, 0.3)},
          {"sphere", sphere_model(), pose_from_axis({160.0, 65.0, 50.0}, {0, 0, 1})},
          {"cone", cone_model(), pose_from_axis({213.074, 110.438, 40.0}, {0, 0, 1})}};
}

// Figure 5.28: radii 48, 50 and 52, 10 mm apart.
std::vector<ScenePart> three_spheres_parts() {
  return {{"sphere48", {48, 48, 48, 1, 1, 0, 0}, pose_from_axis({40, 100, 48}, {0, 0, 1})},
          {"sphere50", {50, 50, 50, 1, 1, 0, 0}, pose_from_axis({148, 100, 50}, {0, 0, 1})},
          {"sphere52", {52, 52, 52, 1, 1, 0, 0}, pose_from_axis({260, 100, 52}, {0, 0, 1})}};
}

// The mallet (parts 0, 1) among look-alikes and two occluding boxes.
std::vector<ScenePart> mallet_scene_parts() {
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY();
  return {
      {"mallet/head", {30, 30, 56, 0.1, 1.0, 0, 0}, pose_from_axis({60, 240, 30}, x)},
      {"mallet/shaft", {12, 10, 120, 0.1, 1.0, 0, 0}, pose_from_axis({60, 70, 30}, y, 1.5708)},
      {"lookalike/drum", {30, 30, 56, 0.1, 1.0, 0, 0}, pose_from_axis({250, 60, 30}, y)},
      {"lookalike/rod", {12, 10, 120, 0.1, 1.0, 0, 0}, pose_from_axis({250, 300, 12}, {1, 0.2, 0})},
      {"hammer/head", {15, 15, 45, 0.1, 1.0, 0, 0}, pose_from_axis({320, 200, 15}, y)},
      {"hammer/shaft", {12, 10, 120, 0.1, 1.0, 0, 0}, pose_from_axis({320, 35, 12}, y)},
      {"occluder/box", {20, 40, 25, 0.1, 0.1, 0, 0}, pose_from_axis({115, 120, 25}, {0, 0, 1})},
      {"occluder/block", {15, 15, 35, 0.1, 0.1, 0, 0}, pose_from_axis({265, -10, 35}, {0, 0, 1})}};
}

Superquadric cylinder_model() { return {30, 30, 50, 0.1, 1.0, 0.0, 0.0}; }
Superquadric box_model() { return {25, 25, 50, 0.1, 0.1, 0.0, 0.0}; }
Superquadric sphere_model() { return {50, 50, 50, 1.0, 1.0, 0.0, 0.0}; }
Superquadric cone_model() { return {20, 20, 40, 0.1, 1.0, -1.0, -1.0}; }

ObjectModel mallet_model() {
  ObjectModel m;
  m.name = "mallet";
  m.parts = {{"head", {30, 30, 56, 0.1, 1.0, 0.0, 0.0}},
             {"shaft", {12, 10, 120, 0.1, 1.0, 0.0, 0.0}}};
  m.links = {
      {0, 1, std::numbers::pi / 2.0, 170.0, std::array<double, 2>{std::numbers::pi / 2.0, 0.0}}};
  return m;
}

Rest rest_of(const Superquadric& sq) {
  return sq.kx != 0.0 || sq.ky != 0.0 ? Rest::kBase : Rest::kAnyFace;
}

TableObject resting_part(const std::string& name, const Superquadric& sq, Rest rest,
                         std::mt19937_64& rng, double p_standing) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // columns: part x, y, z in the table frame
  double up = sq.a3;
  if (rest == Rest::kAnyFace && u(rng) >= p_standing) {
    if (u(rng) < 0.5) {  // x up, z along table x
      R.col(0) = Eigen::Vector3d::UnitZ();
      R.col(1) = Eigen::Vector3d::UnitY();
      R.col(2) = -Eigen::Vector3d::UnitX();
      up = sq.a1;
    } else {  // y up, z along -table y
      R.col(0) = Eigen::Vector3d::UnitX();
      R.col(1) = Eigen::Vector3d::UnitZ();
      R.col(2) = -Eigen::Vector3d::UnitY();
      up = sq.a2;
    }
  }
  // Standing, the lowest point is at -a3 (tapering scales x and y only); lying, at -a1 or -a2.
  TableObject o{name, {ScenePart{name, sq, pose(R, Eigen::Vector3d(0.0, 0.0, up))}}};
  place(o, 0.0, 0.0, 2.0 * std::numbers::pi * u(rng));
  return o;
}

TableObject resting_mallet(const std::string& name, std::mt19937_64& rng, double scale,
                           double head_scale) {
  const ObjectModel m = mallet_model();
  Superquadric head = m.parts[0].shape, shaft = m.parts[1].shape;
  head.a1 *= scale * head_scale, head.a2 *= scale * head_scale, head.a3 *= scale * head_scale;
  shaft.a1 *= scale, shaft.a2 *= scale, shaft.a3 *= scale;
  const double d = m.links[0].distance_mm * scale;
  // Head on its side (centre at its radius), shaft along +x tilting down by alpha until its far
  // end's lower edge meets the table: r - (d + a3) sin(alpha) - a2 cos(alpha) = 0.
  const double r = head.a1, b = shaft.a2, reach_mm = d + shaft.a3;
  double lo = 0.0, hi = 0.5;
  const auto f = [&](double a) { return r - reach_mm * std::sin(a) - b * std::cos(a); };
  if (f(0.0) <= 0.0) hi = 0.0;  // the head is thinner than the shaft: it lies flat
  for (int i = 0; i < 60 && hi > 0.0; ++i) (f(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const double alpha = hi;
  const Eigen::Vector3d axis_u(std::cos(alpha), 0.0, -std::sin(alpha));
  const Eigen::Vector3d w(std::sin(alpha), 0.0, std::cos(alpha));
  const Eigen::Vector3d head_c(0.0, 0.0, std::max(r, b));
  Eigen::Matrix3d Rh, Rs;
  Rh << Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY();
  Rs << Eigen::Vector3d::UnitY(), w, axis_u;
  TableObject o{name,
                {ScenePart{name + "/head", head, pose(Rh, head_c)},
                 ScenePart{name + "/shaft", shaft, pose(Rs, head_c + d * axis_u)}}};
  std::uniform_real_distribution<double> yaw(0.0, 2.0 * std::numbers::pi);
  place(o, 0.0, 0.0, yaw(rng));
  return o;
}

// A look-alike of the model: (1 +- ratio) x all its sizes, or only across or along its axis
// (mallet: the whole mallet or its head).
TableObject lookalike(const ObjectModel& model, double ratio, std::mt19937_64& rng) {
  Draw d{rng};
  const double f = d.chance(0.5) ? 1.0 + ratio : 1.0 - ratio;
  if (model.parts.size() > 1) {
    return d.chance(0.5) ? resting_mallet("lookalike/mallet", d.rng(), f)
                         : resting_mallet("lookalike/mallet", d.rng(), 1.0, f);
  }
  Superquadric sq = model.parts[0].shape;
  const int mode = d.integer(0, 2);
  if (mode != 2) sq.a3 *= f;              // all, or along the axis
  if (mode != 1) sq.a1 *= f, sq.a2 *= f;  // all, or across it
  return resting_part("lookalike/" + model.name, sq, rest_of(sq), d.rng());
}

// Random clutter: cans, boxes, balls, superquadrics, tapered parts standing; for the mallet also
// its lone parts and a hammer (thesis mallet scene). Never within lookalike_min of a model part.
TableObject clutter_object(const ObjectModel& model, double min_ratio, std::mt19937_64& rng) {
  Draw d{rng};
  const bool mallet = model.parts.size() > 1;
  for (;;) {
    const int kind = d.integer(0, mallet ? 7 : 4);
    Superquadric sq;
    std::string name;
    switch (kind) {
      case 0: {
        const double r = d.uniform(15, 45);
        sq = {r, r, d.uniform(20, 60), 0.1, 1.0, 0, 0}, name = "clutter/can";
        break;
      }
      case 1:
        sq = {d.uniform(12, 50), d.uniform(12, 50), d.uniform(12, 50), 0.1, 0.1, 0, 0};
        name = "clutter/box";
        break;
      case 2: {
        const double r = d.uniform(20, 60);
        sq = {r, r, r, 1.0, 1.0, 0, 0}, name = "clutter/ball";
        break;
      }
      case 3:
        sq = {d.uniform(15, 45),
              d.uniform(15, 45),
              d.uniform(15, 45),
              d.uniform(0.3, 1.6),
              d.uniform(0.3, 1.6),
              0,
              0};
        name = "clutter/superquadric";
        break;
      case 4: {
        const double r = d.uniform(15, 35), k = d.uniform(-0.9, 0.4);
        sq = {r, r, d.uniform(20, 50), d.uniform(0.1, 1.0), 1.0, k, k}, name = "clutter/tapered";
        break;
      }
      case 5:
        sq = model.parts[0].shape, name = "clutter/drum";
        return resting_part(name, sq, Rest::kAnyFace, d.rng(), 0.3);
      case 6:
        sq = model.parts[1].shape, name = "clutter/rod";
        return resting_part(name, sq, Rest::kAnyFace, d.rng(), 0.0);
      default:
        return resting_mallet("clutter/hammer", d.rng(), 1.0, 0.5);
    }
    bool close = false;
    for (const ModelPart& p : model.parts) close |= similar_size(sq, p.shape, min_ratio);
    if (!close) return resting_part(name, sq, rest_of(sq), d.rng());
  }
}

void place(TableObject& o, double x, double y, double yaw) {
  const Eigen::Vector3d c = object_bounds(o).center();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0.0) - T.linear() * Eigen::Vector3d(c.x(), c.y(), 0.0);
  for (ScenePart& p : o.parts) p.T_world_part = T * p.T_world_part;
}

OrientedBox oriented_bounds(const ScenePart& p) {
  const Eigen::AlignedBox3d box = part_bounds(p.model);
  return {p.T_world_part * box.center(), p.T_world_part.linear(), 0.5 * box.sizes()};
}

bool boxes_overlap(const OrientedBox& a, const OrientedBox& b, double gap_mm) {
  std::array<Eigen::Vector3d, 15> axes;
  int n = 0;
  for (int i = 0; i < 3; ++i) axes[n++] = a.axes.col(i), axes[n++] = b.axes.col(i);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) axes[n++] = a.axes.col(i).cross(b.axes.col(j));
  }
  const Eigen::Vector3d t = b.centre - a.centre;
  for (const Eigen::Vector3d& axis : axes) {
    const double len = axis.norm();
    if (len < 1e-9) continue;  // parallel edges: covered by the face axes
    const Eigen::Vector3d L = axis / len;
    double ra = 0.0, rb = 0.0;
    for (int k = 0; k < 3; ++k) {
      ra += a.half[k] * std::abs(L.dot(a.axes.col(k)));
      rb += b.half[k] * std::abs(L.dot(b.axes.col(k)));
    }
    if (std::abs(L.dot(t)) >= ra + rb + gap_mm) return false;  // a separating axis
  }
  return true;
}

bool objects_overlap(const TableObject& a, const TableObject& b, double gap_mm) {
  for (const ScenePart& p : a.parts) {
    for (const ScenePart& q : b.parts) {
      if (boxes_overlap(oriented_bounds(p), oriented_bounds(q), gap_mm)) return true;
    }
  }
  return false;
}

Eigen::AlignedBox3d object_bounds(const TableObject& o) {
  Eigen::AlignedBox3d box;
  for (const ScenePart& p : o.parts) {
    const Eigen::AlignedBox3d b = part_bounds(p.model);
    for (int c = 0; c < 8; ++c) {
      box.extend(p.T_world_part * b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
    }
  }
  return box;
}

double reach(const TableObject& o, const Eigen::Vector3d& u) {
  double best = -std::numeric_limits<double>::infinity();
  for (const ScenePart& p : o.parts) {
    const OrientedBox b = oriented_bounds(p);
    double r = u.dot(b.centre);
    for (int k = 0; k < 3; ++k) r += b.half[k] * std::abs(u.dot(b.axes.col(k)));
    best = std::max(best, r);
  }
  return best;
}

bool similar_size(const Superquadric& a, const Superquadric& b, double ratio) {
  std::array<double, 3> x{a.a1, a.a2, a.a3}, y{b.a1, b.a2, b.a3};
  std::sort(x.begin(), x.end());
  std::sort(y.begin(), y.end());
  for (int i = 0; i < 3; ++i) {
    if (std::abs(x[i] / y[i] - 1.0) >= ratio) return false;
  }
  return true;
}

}  // namespace rangefit::sim
