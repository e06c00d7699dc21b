#pragma once
// The daily-life objects of the thesis's detection examples as superquadric models with their
// sizes from the tables (thesis 5.2.2, table 5.6: cuboid, sphere, cylinder, pyramid, wooden bowl,
// computer mouse, mug, cup, sponge; 5.2.3, table 5.7: the mug as body and handle, linked at 90 deg
// and 50 mm), and how each rests on the table: one part as sim::resting_part puts it (tapered
// parts on their base), the two-part mug standing with its handle at the side of the body.

#include <random>
#include <string>
#include <vector>

#include "detect/object/object_model.hpp"
#include "sim/scene_objects.hpp"

namespace rangefit::sim {

struct DailyObject {
  std::string name;   // "cuboid", ..., "mug-2" (the two-part mug of table 5.7)
  std::string table;  // "5.6" or "5.7"
  ObjectModel model;  // one part, or the mug's body (part 0) and handle (part 1) with their link
};

// All ten, table 5.6 in its order, then the two-part mug.
std::vector<DailyObject> daily_life_objects();

// The two-part mug standing on the table at (0, 0), yaw 0: the body's axis vertical, the
// handle's centre half way up the body and `link.distance_mm` from its axis along +x, its x-axis
// pointing away from the body, its y-axis up and its thin z-axis across (the link's 90 deg).
// Most of the handle's inner half lies inside the body, as the thesis's flattened handle does.
TableObject standing_mug(const std::string& name, const ObjectModel& mug);

// The object resting at table position (x, y) with a drawn yaw: one part by resting_part (face
// drawn when untapered, z up with probability p_standing), the mug by standing_mug.
TableObject resting_daily_object(const DailyObject& object, double x, double y,
                                 std::mt19937_64& rng, double p_standing = 0.5);

}  // namespace rangefit::sim
