#include "daemon/cell/fuse_views.hpp"

#include <algorithm>
#include <optional>

namespace rangefit::daemon {

ScanOutcome fuse_views(std::span<ScanOutcome> views, std::span<const std::string> names,
                       const FuseOptions& options) {
  ScanOutcome fused;
  for (std::size_t k = 0; k < views.size(); ++k) {
    ScanOutcome& view = views[k];
    const std::string& name = names[k];
    if (!view.status) {
      fused.status =
          options.named ? view.status : hal::Status::Error(name + ": " + view.status.message);
      return fused;
    }
    if (k == 0) {
      fused.cloud.frame_id = view.cloud.frame_id;
      fused.sensor = view.sensor;
    } else if (view.cloud.frame_id != fused.cloud.frame_id) {
      fused.status =
          hal::Status::Error(name + ": scans into frame \"" + view.cloud.frame_id +
                             "\", the first sensor into \"" + fused.cloud.frame_id + "\"");
      return fused;
    }
    if (k > 0 && options.cameras) {
      const std::optional<SensorView> both =
          with_second_camera(fused.sensor.view, view.sensor.view);
      if (!both) {
        fused.status =
            hal::Status::Error(name + ": not a second camera of " + names.front() +
                               "'s laser sweep (the same plane, axis and configured sweep range)");
        return fused;
      }
      fused.sensor.view = *both;
    }
    append_view(fused.cloud, view.cloud);
    if (options.keep_apart) fused.views.push_back({name, std::move(view.cloud), view.sensor});
    fused.acquired_wall_ns = std::max(fused.acquired_wall_ns, view.acquired_wall_ns);
  }
  // Spooled and replayed with the cloud: the cameras' view describes every point of it.
  if (options.cameras) fused.cloud.sensor = fused.sensor.view;
  fused.status = hal::Status::Ok();
  return fused;
}

}  // namespace rangefit::daemon
