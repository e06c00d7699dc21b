#pragma once
// Generated test plate with bore holes (thesis 4.2.1, fig. 4.17 and 4.13): a row of square cells,
// each with one bore of a given kind. The plate's top face is z = 0 (object frame), its bottom
// z = -thickness; cell i is centred at x = (i + 0.5) * cell - length / 2, y = 0.

#include <string>
#include <vector>

#include "io/triangle_mesh.hpp"
#include "sim/scene.hpp"

namespace rangefit::sim {

enum class BoreKind { kStraight, kSlanted, kChamfered, kRounded, kNotched };

struct BoreSpec {
  std::string name;
  BoreKind kind = BoreKind::kStraight;
  double diameter_mm = 12.0;     // 4..38 in the shipped scenes
  double slant_rad = 0.0;        // kSlanted: axis tilt about the plate's y-axis
  double edge_mm = 1.0;          // kChamfered: 45 deg chamfer width; kRounded: fillet radius
  int notches = 6;               // kNotched: radial notches, equally spaced
  double notch_depth_mm = 2.0;   // kNotched: radial depth
  double notch_width_rad = 0.2;  // kNotched: angular width of each notch
};

struct BorePlateSpec {
  double cell_mm = 60.0;  // cell side; also the plate's width in y
  double thickness_mm = 20.0;
  int segments = 256;           // points per bore ring; multiple of 8
  std::vector<BoreSpec> bores;  // one cell each, in order along x
};

// The mesh in the plate frame and each bore's ground truth in the same frame. Returns an empty
// mesh when the spec is invalid (a bore does not fit its cell, no bores, bad sizes); `error` then
// says why.
struct BorePlate {
  io::TriangleMesh mesh;
  std::vector<BoreTruth> bores;
  std::string error;
};

BorePlate make_bore_plate(const BorePlateSpec& spec);

const char* to_string(BoreKind kind);
bool parse_bore_kind(const std::string& text, BoreKind& kind);

}  // namespace rangefit::sim
