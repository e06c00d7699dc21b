#include "sim/bore_plate_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rangefit::sim {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

struct Level {
  double depth;  // >= 0, below the top face
  double widen;  // added to the radius at this depth (chamfer, fillet)
};

// Radius profile along the bore: top (depth 0) to bottom (depth = thickness).
std::vector<Level> profile(const BoreSpec& b, double thickness) {
  std::vector<Level> levels;
  const double e = std::min(b.edge_mm, 0.5 * thickness);
  if (b.kind == BoreKind::kChamfered) {
    levels = {{0.0, e}, {e, 0.0}};
  } else if (b.kind == BoreKind::kRounded) {
    constexpr int kSteps = 8;  // quarter circle of radius e tangent to wall and top face
    for (int k = 0; k <= kSteps; ++k) {
      const double phi = 0.5 * kPi * k / kSteps;
      levels.push_back({e - e * std::cos(phi), e - e * std::sin(phi)});
    }
  } else {
    levels = {{0.0, 0.0}};
  }
  levels.push_back({thickness, 0.0});
  return levels;
}

// Point k of the bore's ring at one level, in the plate frame (cell centre cx).
Vector3d ring_point(const BoreSpec& b, double cx, const Level& lv, int k, int n) {
  const double theta = 2.0 * kPi * k / n;
  double r = 0.5 * b.diameter_mm + lv.widen;
  if (b.kind == BoreKind::kNotched && b.notches > 0) {
    const double pitch = 2.0 * kPi / b.notches;
    const double off = std::remainder(theta, pitch);
    if (std::abs(off) <= 0.5 * b.notch_width_rad) r += b.notch_depth_mm;
  }
  if (b.kind == BoreKind::kSlanted) {
    // Horizontal section of a circular cylinder of radius r tilted by a: an ellipse with
    // semi-axes r / cos(a) in x and r in y, centre moving along x by depth * tan(a).
    const double a = b.slant_rad;
    return {cx + lv.depth * std::tan(a) + r / std::cos(a) * std::cos(theta), r * std::sin(theta),
            -lv.depth};
  }
  return {cx + r * std::cos(theta), r * std::sin(theta), -lv.depth};
}

// Point on the square cell boundary (half side h) in the direction theta, at height z.
Vector3d square_point(double cx, double h, double theta, double z) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double scale = h / std::max(std::abs(c), std::abs(s));
  return {cx + scale * c, scale * s, z};
}

void add_quad(io::TriangleMesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c,
              std::uint32_t d) {  // a-b-c-d counter-clockwise seen from outside
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}

}  // namespace

const char* to_string(BoreKind kind) {
  switch (kind) {
    case BoreKind::kStraight:
      return "straight";
    case BoreKind::kSlanted:
      return "slanted";
    case BoreKind::kChamfered:
      return "chamfered";
    case BoreKind::kRounded:
      return "rounded";
    case BoreKind::kNotched:
      return "notched";
  }
  return "unknown";
}

bool parse_bore_kind(const std::string& text, BoreKind& kind) {
  for (BoreKind k : {BoreKind::kStraight, BoreKind::kSlanted, BoreKind::kChamfered,
                     BoreKind::kRounded, BoreKind::kNotched}) {
    if (text == to_string(k)) {
      kind = k;
      return true;
    }
  }
  return false;
}

BorePlate make_bore_plate(const BorePlateSpec& spec) {
  BorePlate out;
  const int n = spec.segments;
  const double h = 0.5 * spec.cell_mm;
  const double t = spec.thickness_mm;
  if (spec.bores.empty()) out.error = "a bore plate needs at least one bore";
  if (n < 8 || n % 8 != 0) out.error = "segments must be a positive multiple of 8";
  if (!(spec.cell_mm > 0.0) || !(t > 0.0)) out.error = "cell and thickness must be positive";
  for (const BoreSpec& b : spec.bores) {
    double reach = 0.5 * b.diameter_mm + std::max(b.edge_mm, 0.0) +
                   (b.kind == BoreKind::kNotched ? b.notch_depth_mm : 0.0);
    if (b.kind == BoreKind::kSlanted)
      reach = reach / std::cos(b.slant_rad) + t * std::tan(std::abs(b.slant_rad));
    if (!(b.diameter_mm > 0.0) || reach >= 0.95 * h) {
      out.error =
          "bore '" + b.name + "' does not fit a " + std::to_string(spec.cell_mm) + " mm cell";
    }
    if (b.kind == BoreKind::kSlanted && !(std::abs(b.slant_rad) < 0.4 * kPi)) {
      out.error = "bore '" + b.name + "': slant must be below 72 deg";
    }
  }
  if (!out.error.empty()) return out;

  io::TriangleMesh& m = out.mesh;
  auto add = [&](const Vector3d& v) {
    m.vertices.push_back(v);
    return static_cast<std::uint32_t>(m.vertices.size() - 1);
  };
  const double length = spec.cell_mm * static_cast<double>(spec.bores.size());
  for (std::size_t i = 0; i < spec.bores.size(); ++i) {
    const BoreSpec& b = spec.bores[i];
    const double cx = (static_cast<double>(i) + 0.5) * spec.cell_mm - 0.5 * length;
    const std::vector<Level> levels = profile(b, t);
    // Rings of the bore wall, top to bottom.
    std::vector<std::uint32_t> rings;
    for (const Level& lv : levels) {
      rings.push_back(static_cast<std::uint32_t>(m.vertices.size()));
      for (int k = 0; k < n; ++k) add(ring_point(b, cx, lv, k, n));
    }
    const auto top_sq = static_cast<std::uint32_t>(m.vertices.size());
    for (int k = 0; k < n; ++k) add(square_point(cx, h, 2.0 * kPi * k / n, 0.0));
    const auto bot_sq = static_cast<std::uint32_t>(m.vertices.size());
    for (int k = 0; k < n; ++k) add(square_point(cx, h, 2.0 * kPi * k / n, -t));
    const std::uint32_t top_ring = rings.front(), bot_ring = rings.back();
    for (int k = 0; k < n; ++k) {
      const auto k0 = static_cast<std::uint32_t>(k), k1 = static_cast<std::uint32_t>((k + 1) % n);
      add_quad(m, top_ring + k0, top_sq + k0, top_sq + k1, top_ring + k1);  // top face, +z
      add_quad(m, bot_ring + k1, bot_sq + k1, bot_sq + k0, bot_ring + k0);  // bottom face, -z
      for (std::size_t l = 0; l + 1 < rings.size(); ++l) {                  // wall, facing the axis
        add_quad(m, rings[l] + k0, rings[l] + k1, rings[l + 1] + k1, rings[l + 1] + k0);
      }
    }
    // Side faces where the cell is on the plate's border (y = +-h; x = ends).
    auto side = [&](const Vector3d& a, const Vector3d& c) {  // a, c: top corners, ccw from outside
      add_quad(m, add(a), add(Vector3d(a.x(), a.y(), -t)), add(Vector3d(c.x(), c.y(), -t)), add(c));
    };
    side({cx + h, -h, 0.0}, {cx - h, -h, 0.0});
    side({cx - h, h, 0.0}, {cx + h, h, 0.0});
    if (i == 0) side({cx - h, -h, 0.0}, {cx - h, h, 0.0});
    if (i + 1 == spec.bores.size()) side({cx + h, h, 0.0}, {cx + h, -h, 0.0});

    BoreTruth truth;
    truth.name = b.name;
    truth.kind = to_string(b.kind);
    truth.diameter_mm = b.diameter_mm;
    truth.opening_mm = Vector3d(cx, 0.0, 0.0);
    truth.axis = b.kind == BoreKind::kSlanted
                     ? Vector3d(std::sin(b.slant_rad), 0.0, -std::cos(b.slant_rad))
                     : Vector3d(0.0, 0.0, -1.0);
    out.bores.push_back(truth);
  }
  return out;
}

}  // namespace rangefit::sim
