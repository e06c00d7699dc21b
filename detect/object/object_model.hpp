#pragma once
// A known object as the detector sees it (thesis ch. 5): one or a few tapered superquadric parts
// and, for compound objects, the links between them (5.1.3: the angle between the two z-axes and
// the distance between the two centres). A plain value type; io/object_model_file reads it.

#include <cstddef>
#include <string>
#include <vector>

#include "detect/object/superquadric.hpp"

namespace rangefit {

struct ModelPart {
  std::string name;
  Superquadric shape;
};

struct PartLink {
  std::size_t first = 0;     // index into ObjectModel::parts
  std::size_t second = 0;    // index into ObjectModel::parts
  double angle_rad = 0.0;    // nominal angle alpha_k between the parts' z-axes (eq. 5.5)
  double distance_mm = 0.0;  // nominal distance d_k between the part centres (eq. 5.6)
};

struct ObjectModel {
  std::string name;
  std::vector<ModelPart> parts;
  std::vector<PartLink> links;
};

}  // namespace rangefit
