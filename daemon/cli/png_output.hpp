#pragma once
// `--png PIC.png` of `rangefit bore` and `rangefit object`: the scan and what was found in it as
// one picture (render/render.hpp), seen from the sensor when the options say where it was.

#include <string>

#include "detect/bore/bore_options.hpp"
#include "detect/bore/bore_result.hpp"
#include "detect/object/object_detector.hpp"
#include "detect/common/point_cloud.hpp"

namespace rangefit::cli {

// Nothing when path is empty. False, with the reason on stderr, when the file cannot be written.
bool write_png_if_asked(const std::string& path, const PointCloud& cloud, const BoreResult& result,
                        const BoreOptions& options);
bool write_png_if_asked(const std::string& path, const PointCloud& cloud, const ObjectModel& model,
                        const ObjectDetectResult& result, const ObjectDetectOptions& options);

}  // namespace rangefit::cli
