#pragma once
// Whether a part could rest on the table as posed: beyond the thesis. A cone fitted onto a box
// (its flat base on the box's top face, its apex down into the box) or lying with its axis level
// (on one point of its base's rim) explains the scan as well as a true cone does, but no cone
// stays like that: it turns onto its base or its side. The part is let settle: turned, a few
// degrees at a time, about the level axis that lowers its centroid most above the table (its
// lowest point kept on the table), until no turn lowers it. A part that rests turns by no more
// than its fit's error; one balanced on an apex or an edge topples.
//
// Only visibly tapered single parts are asked (object_detector.cpp): a box or a can posed tilted
// onto an edge may lean on a neighbour (fig. 5.18's box stands 20 deg onto one), while a cone's
// taper is what a box's top face cannot tell apart from its base.

#include <Eigen/Core>

#include "detect/object/superquadric.hpp"

namespace rangefit {

// The centroid of the part's volume (uniform density) in its own frame: on its axis, shifted
// towards the wide end by the taper (a full cone's a quarter of its height above its base).
Eigen::Vector3d part_centroid(const Superquadric& part);

// The angle (rad) through which the part at orientation R_world_part turns as it settles onto
// a table whose normal is `up` (see above); it stops counting past limit_rad.
double settle_angle_rad(const Superquadric& part, const Eigen::Matrix3d& R_world_part,
                        const Eigen::Vector3d& up, double limit_rad);

}  // namespace rangefit
