#pragma once
// Colour scales of the point colouring: perceptually even for height (viridis), and a traffic
// light for the distance to the model, so good fits read green at a glance.

#include "render/image.hpp"

namespace rangefit::render {

// t in [0, 1] (clamped): dark violet to yellow.
Rgb height_colour(double t);
// t in [0, 1] (clamped): green (on the model) through yellow to red.
Rgb distance_colour(double t);
// Points far from every model in kModelDistance.
inline constexpr Rgb kFarColour{88, 90, 98};

}  // namespace rangefit::render
