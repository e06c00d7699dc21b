#include "daemon/service/request_validation.hpp"

#include <cmath>
#include <numbers>

#include "daemon/service/scan_types.hpp"

namespace rangefit::daemon {

std::string check_name(std::string_view text, std::string_view what, std::size_t max_length) {
  if (text.empty()) return std::string(what) + " is empty";
  if (text.size() > max_length) {
    return std::string(what) + " longer than " + std::to_string(max_length) + " characters (" +
           std::to_string(text.size()) + ")";
  }
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c > 0x7e) {
      return std::string(what) + " has a non-printable character at " + std::to_string(i) +
             " (only printable ASCII)";
    }
  }
  return "";
}

namespace {

constexpr double kMaxMm = 1e6;  // as the CLI's vectors (kMaxCoordinateMm)

bool finite_within(const Eigen::Vector3d& v, double limit) {
  return v.allFinite() && v.cwiseAbs().maxCoeff() <= limit;
}

std::string check_sensor_knowledge(ScanRequest& request) {
  if (request.view_dir) {
    if (!finite_within(*request.view_dir, kMaxMm) || !(request.view_dir->norm() > 1e-9))
      return "view_dir must be finite and not zero";
    request.view_dir->normalize();
  }
  if (request.sensor_position && !finite_within(*request.sensor_position, kMaxMm))
    return "sensor_position must be finite, within +-1e6 mm";
  return "";
}

// A cone or elliptic bore's model; the detector refuses the rest (kBadShape) with its reason.
std::string check_bore_shape(const BorePrior& bore) {
  if (!std::isfinite(bore.half_angle_rad) || bore.half_angle_rad < 0.0 ||
      bore.half_angle_rad >= 1.396)
    return "bore half_angle_rad must be in 0 .. 1.396 rad (80 deg; 0: no cone)";
  if (!std::isfinite(bore.cylinder_radius_mm) || bore.cylinder_radius_mm < 0.0 ||
      bore.cylinder_radius_mm > 1e5)
    return "bore cylinder_radius_mm must be in 0 .. 1e5 mm (0: none)";
  if (!std::isfinite(bore.radius2_mm) || bore.radius2_mm < 0.0 || bore.radius2_mm > 1e5)
    return "bore radius2_mm must be in 0 .. 1e5 mm (0: circular)";
  if (bore.radius2_mm > 0.0 &&
      !(bore.major_axis && bore.major_axis->allFinite() && bore.major_axis->norm() > 1e-9))
    return "bore radius2_mm needs a finite, non-zero major_axis";
  return "";
}

std::string check_bore(BorePrior& bore) {
  if (!(bore.radius_mm > 0.0)) return "bore_radius must be > 0";
  if (!(bore.axis.norm() > 1e-9)) return "bore_axis must not be zero";
  bore.axis.normalize();
  if (bore.plane_normal) bore.plane_normal->normalize();
  if (bore.walls.empty()) bore.walls = "inner";
  if (bore.walls != "inner" && bore.walls != "outer" && bore.walls != "both")
    return "bore walls must be \"inner\", \"outer\" or \"both\"";
  if (!std::isfinite(bore.outer_radius_mm) || bore.outer_radius_mm < 0.0 ||
      bore.outer_radius_mm > 1e5)
    return "bore outer_radius must be in 0 .. 1e5 mm (0: none)";
  if (bore.walls == "both" && !(bore.outer_radius_mm > bore.radius_mm))
    return "bore walls \"both\" needs outer_radius larger than radius";
  if (!std::isfinite(bore.normal_keep) || bore.normal_keep < 0.0 || bore.normal_keep > 1.0)
    return "bore normal_keep must be in (0, 1] (0: all)";
  return check_bore_shape(bore);
}

// The kind whose calibration body a calibrate target names (by its name or its CLI spelling,
// as `rangefit calibrate pantilt`); null: none the service calibrates.
const SensorKind* target_kind(const CalibrationTarget& t) {
  const SensorKind* k = find_sensor_kind(t.kind);
  return k != nullptr && k->calibrated_by_service ? k : nullptr;
}

// The ids of earlier requests a calibration over several requests joins.
std::string check_scans(const CalibrationTarget& t, const std::string& own_id) {
  if (t.scans.size() > kMaxCalibrationScans) {
    return "scans names at most " + std::to_string(kMaxCalibrationScans) + " earlier requests";
  }
  for (std::size_t i = 0; i < t.scans.size(); ++i) {
    if (auto why = check_name(t.scans[i], "scans[" + std::to_string(i) + "]", kMaxRequestIdLength);
        !why.empty())
      return why;
    if (t.scans[i] == own_id) return "scans names this request itself";
    for (std::size_t k = 0; k < i; ++k) {
      if (t.scans[k] == t.scans[i]) return "scans names a request twice";
    }
  }
  return "";
}

std::string check_css_target(const CalibrationTarget& t) {
  if (!(t.radius_mm > 0.0 && t.radius_mm <= 1e4))
    return "calibrate css needs the sphere's radius_mm, in (0, 1e4] mm";
  if (!t.T_base_joint) {
    return "calibrate css needs robot_pose: the last joint's frame in the robot base at this "
           "scan, as the robot controller reports it";
  }
  if (!t.T_base_joint->matrix().allFinite() ||
      !finite_within(t.T_base_joint->translation(), kMaxMm))
    return "robot_pose must be finite, within +-1e6 mm";
  return "";
}

// The cube (stripe, pantilt) and, for the head, the tilt it is held at.
std::string check_cube_target(const CalibrationTarget& t, bool pan_tilt) {
  if (!(t.edge_mm > 0.0 && t.edge_mm <= kMaxMm && t.bar_mm > 0.0 && t.bar_mm < 0.5 * t.edge_mm))
    return "target size must be an edge > 0 and a bar in (0, edge / 2), mm";
  if (!t.T_table_target.matrix().allFinite() ||
      !finite_within(t.T_table_target.translation(), kMaxMm))
    return "target pose must be finite";
  if (t.tilt_rad && !pan_tilt) return "tilt_rad is for the pantilt target only";
  if (t.tilt_rad && !(std::abs(*t.tilt_rad) <= 0.5 * std::numbers::pi))
    return "tilt_rad must be within +-pi/2";
  return "";
}

// Completes the target's kind to its CLI spelling ("stripe", "pantilt", "css"): the name the
// detector, the files and `rangefit calibrate` use.
std::string check_target(CalibrationTarget& t, const std::string& own_id) {
  const SensorKind* k = target_kind(t);
  if (k == nullptr) {
    return "calibrate target must be \"stripe\" (the hollow cube on the stripe cell), "
           "\"pantilt\" (the cube before the pan-tilt head, one request per tilt) or \"css\" (a "
           "precision sphere, one request per robot pose)";
  }
  t.kind = *k->cli_name != '\0' ? k->cli_name : k->name;
  if (auto why = check_scans(t, own_id); !why.empty()) return why;
  if (t.kind == "css") return check_css_target(t);
  return check_cube_target(t, t.kind == "pantilt");
}

// Several sensors' scans fused: each a configured device, named once, scanning its configured
// sweep (a request's sweep is in one device's units). The first is the sensor. Learn fuses any
// views; object detection two cameras of one laser plane, a stripe cell's or a pan-tilt head's
// (the scan merges their views, DeviceBackend::scan_views); a stripe calibration the cameras of
// its laser plane (each solved on its own sweep, together as one rig).
std::string check_views(ScanRequest& request, const DaemonConfig& config) {
  if (request.sensors.empty()) return "";
  if (request.kind == DetectKind::kObject) {
    if (request.sensors.size() != 2) {
      return "sensors: an object request fuses the two cameras of one laser plane; name two";
    }
    const DeviceConfig* first = config.device(request.sensors.front());
    for (const std::string& name : request.sensors) {
      const DeviceConfig* d = config.device(name);
      if (d == nullptr) continue;  // named below
      if (d->kind != DeviceKind("stripe") && d->kind != DeviceKind("pan_tilt")) {
        return "sensors: \"" + name + "\" is a " + std::string(d->kind.name()) +
               "; an object request fuses the cameras of a stripe cell or a pan-tilt head";
      }
      if (first != nullptr && d->kind != first->kind) {
        return "sensors: \"" + name + "\" is a " + std::string(d->kind.name()) + ", \"" +
               first->name + "\" a " + std::string(first->kind.name()) +
               "; an object request fuses two cameras of one laser plane";
      }
    }
  } else if (request.kind == DetectKind::kCalibrate) {
    const SensorKind* target = target_kind(request.target);
    if (target == nullptr || DeviceKind(*target) != DeviceKind("stripe")) {
      return "sensors: a calibrate request takes several sensors for the stripe target only (the "
             "cameras of its laser plane, one sweep); give one sensor";
    }
    for (const std::string& name : request.sensors) {
      const DeviceConfig* d = config.device(name);
      if (d != nullptr && d->kind != DeviceKind("stripe")) {
        return "sensors: \"" + name + "\" is a " + std::string(d->kind.name()) +
               "; a stripe calibration takes the cameras of its laser plane";
      }
    }
  } else if (request.kind != DetectKind::kLearn) {
    return "sensors (several scans fused) is for learn, object and stripe calibrate requests; "
           "give one sensor";
  }
  if (request.sensors.size() > kMaxViews) {
    return "sensors: at most " + std::to_string(kMaxViews) + " scans are fused";
  }
  if (!request.sensor.empty() && request.sensor != request.sensors.front()) {
    return "give sensor or sensors, not both";
  }
  for (std::size_t k = 0; k < request.sensors.size(); ++k) {
    const std::string& name = request.sensors[k];
    if (auto why = check_name(name, "sensors", kMaxNameLength); !why.empty()) return why;
    if (config.device(name) == nullptr) return "unknown sensor \"" + name + "\" in sensors";
    for (std::size_t j = 0; j < k; ++j) {
      if (request.sensors[j] == name) return "sensor \"" + name + "\" named twice in sensors";
    }
  }
  if (request.sweep_start != 0.0 || request.sweep_end != 0.0 || request.sweep_speed != 0.0) {
    return "with sensors each scans its configured sweep: leave sweep out";
  }
  request.sensor = request.sensors.front();
  return "";
}

std::string first_device_of_kind(const DaemonConfig& config, const DeviceKind& kind) {
  for (const auto& d : config.devices) {
    if (d.kind == kind) return d.name;
  }
  return "";
}

}  // namespace

std::string validate_request(ScanRequest& request, const DaemonConfig& config) {
  if (auto why = check_name(request.id, "request_id", kMaxRequestIdLength); !why.empty())
    return why;
  if (request.kind == DetectKind::kObject) {
    if (auto why = check_name(request.model, "model", kMaxNameLength); !why.empty()) return why;
  }
  if (!request.sensor.empty()) {  // empty: the configured default
    if (auto why = check_name(request.sensor, "sensor", kMaxNameLength); !why.empty()) return why;
  }
  if (auto why = check_views(request, config); !why.empty()) return why;
  if (auto why = check_sensor_knowledge(request); !why.empty()) return why;
  if (request.kind == DetectKind::kBore) {
    if (auto why = check_bore(request.bore); !why.empty()) return why;
  } else if (request.kind == DetectKind::kLearn) {
    if (request.parts < 0 || request.parts > 2) return "parts must be 1 or 2 (0: 1)";
    if (request.model.empty()) request.model = "learnt";
    if (auto why = check_name(request.model, "model", kMaxNameLength); !why.empty()) return why;
  } else if (request.kind == DetectKind::kCalibrate) {
    if (auto why = check_target(request.target, request.id); !why.empty()) return why;
    if (request.sensor.empty()) {
      request.sensor = first_device_of_kind(config, *target_kind(request.target));
    }
  } else if (config.object(request.model) == nullptr) {
    std::string known;
    for (const auto& o : config.objects) known += (known.empty() ? "" : ", ") + o.name;
    return "unknown object model \"" + request.model +
           "\" (configured: " + (known.empty() ? "none" : known) + ")";
  }
  if (request.instances == 0) request.instances = 1;
  if (request.instances < 1 || request.instances > 1000) return "instances must be in 1 .. 1000";
  if (request.hypotheses < 0 || request.hypotheses > 10000) {
    return "hypotheses must be in 0 .. 10000 (0: the detector's default)";
  }
  if (request.trials < 0 || request.trials > 10000) {
    return "trials must be in 0 .. 10000 (0: the detector's default)";
  }
  if (request.sensor.empty()) {
    request.sensor = request.kind == DetectKind::kBore ? config.service.bore_sensor
                                                       : config.service.object_sensor;
  }
  const DeviceConfig* device = config.device(request.sensor);
  if (device == nullptr) {
    return request.sensor.empty() ? std::string("no sensor given and no default configured")
                                  : "unknown sensor \"" + request.sensor + "\"";
  }
  if (request.kind == DetectKind::kCalibrate && device->kind != *target_kind(request.target)) {
    return "calibrate " + request.target.kind + " needs a " +
           std::string(target_kind(request.target)->name) + " sensor; \"" + request.sensor +
           "\" is a " + std::string(device->kind.name());
  }
  if (!std::isfinite(request.sweep_start) || !std::isfinite(request.sweep_end) ||
      !std::isfinite(request.sweep_speed) || request.sweep_speed < 0.0) {
    return "sweep values must be finite and sweep_speed >= 0";
  }
  convert_sweep_units(request, device->kind->sweep_linear, /*to_wire=*/false);
  if (request.sweep_start == request.sweep_end) {  // the device's configured sweep
    request.sweep_start = device->sweep_start;
    request.sweep_end = device->sweep_end;
  }
  if (request.sweep_speed == 0.0) request.sweep_speed = device->sweep_speed;
  // The sweep decides how many points the scan fuses (a CSS sweep of +-30 rad fused 3.6 M
  // points): the limits of the config's sweeps, one turn each way or 10 m.
  const bool linear = device->kind->sweep_linear;
  const double limit = linear ? 1e4 : 6.283185307179586;
  if (std::abs(request.sweep_start) > limit || std::abs(request.sweep_end) > limit) {
    return linear ? "sweep_start and sweep_end must be within +-10 m"
                  : "sweep_start and sweep_end must be within +-2 pi rad (one turn)";
  }
  if (request.sweep_speed > (linear ? 1e5 : 100.0)) {
    return linear ? "sweep_speed must be at most 100 m/s" : "sweep_speed must be at most 100 rad/s";
  }
  return "";
}

}  // namespace rangefit::daemon
