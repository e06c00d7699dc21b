#pragma once
// Several sensors' scans of one request fused into one: the views are in one world frame, so
// their points are appended (detect/common/point_cloud.hpp append_view). For object detection
// the views are the cameras of one laser plane, and the fused view is the first's with the
// second's camera (with_second_camera): a point either camera saw is in the cloud, and the
// detector must know that either could have seen it. Used by rangefitd's backend and by
// `rangefit simulate`, so that both fuse alike.

#include <span>
#include <string>
#include <vector>

#include "daemon/service/pipeline.hpp"

namespace rangefit::daemon {

struct FuseOptions {
  // The views are the cameras of one laser plane: their sensor views merge (with_second_camera).
  bool cameras = false;
  // A failed view's error names its devices already (a shared sweep's): not prefixed again.
  bool named = false;
  // Each view also goes apart into ScanOutcome::views (a calibration solves each camera's own
  // sweep).
  bool keep_apart = false;
};

// views[k] came from the device names[k]. The first view that failed fails the fusion, its
// error prefixed with its name unless options.named; the views before it are fused and go with
// the error, so the spool keeps them. Also an error: a view in another frame, or (cameras) one
// that is not a further camera of the first's laser sweep. The fused cloud has no grid; the first
// view's description goes with it.
ScanOutcome fuse_views(std::span<ScanOutcome> views, std::span<const std::string> names,
                       const FuseOptions& options);

}  // namespace rangefit::daemon
