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

// views[k] came from the device names[k]. The first view that failed fails the fusion, its
// error prefixed with its name unless `named` (the error names the devices already); the views
// before it are fused and go with the error, so the spool keeps them. Also an error: a view in
// another frame, or (cameras = true) one that is not a further camera of the first's laser sweep.
// The fused cloud has no grid; the first view's description goes with it.
ScanOutcome fuse_views(std::span<ScanOutcome> views, std::span<const std::string> names,
                       bool cameras, bool named = false);

}  // namespace rangefit::daemon
