#pragma once
// The picture of a service result (render/): the scan with the fitted bore or object parts drawn
// over it and a legend with the numbers. The service writes one into each spool entry
// (picture.png, [spool] pictures), `rangefit replay --png` and `rangefit render --result` draw
// the same from a spooled result.

#include <filesystem>
#include <optional>
#include <string>

#include "daemon/service/scan_types.hpp"
#include "detect/object/object_model.hpp"
#include "detect/common/point_cloud.hpp"
#include "render/drawing.hpp"

namespace rangefit::daemon {

// The result's bores and parts with their poses, and the legend. model: the shapes of an object
// result's parts (null for bores); throws std::invalid_argument when a part is not in it.
render::Drawing result_drawing(const DetectionResult& result, const ObjectModel* model);

// Renders and writes path; false and *error when it cannot (an unknown part, an unwritable
// file). Frees the font caches afterwards (render::release_font_caches).
bool write_result_picture(const std::filesystem::path& path, const PointCloud& cloud,
                          const DetectionResult& result, const ObjectModel* model,
                          std::string* error);

}  // namespace rangefit::daemon
