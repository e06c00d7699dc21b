#include "daemon/cli/remote/request_command.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "daemon/cli/cli_options.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/cli/option_checks.hpp"
#include "daemon/dds/client.hpp"
#include "daemon/service/json_codec.hpp"
#include "daemon/service/result_outcome.hpp"
#include "daemon/service/ros_env.hpp"
#include "hal/rpy.hpp"

namespace rangefit::cli {
namespace {

struct RequestArgs {
  std::optional<std::uint32_t> domain;  // none: ROS_DOMAIN_ID, else 0
  std::string id;
  std::string model;
  std::string sensor;
  bool linear = false;
  std::array<double, 3> position_mm{};
  std::array<double, 3> axis{0, 0, 1};
  double radius_mm = 0;
  std::array<double, 3> sweep{};  // start, end, speed
  double timeout_s = 120;
  std::vector<double> plane_normal;     // bore: optional
  double outer_radius_mm = 0;           // bore: a pipe's outer wall
  std::string walls;                    // bore: inner | outer | both
  double normal_keep = 0;               // bore: 0: all
  double half_angle = 0;                // bore: a cone's half-angle, rad
  double cylinder_radius_mm = 0;        // bore: the cylinder a countersink ends in
  double radius2_mm = 0;                // bore: an ellipse's second semi-axis
  std::vector<double> major_axis;       // bore: the ellipse's --cad-radius direction
  std::vector<double> view_dir;         // bore: optional, replaces the sensor's
  std::vector<double> sensor_position;  // bore --sensor-position, object --viewpoint
  int instances = 1;
  int hypotheses = 0;
  int trials = 0;
  std::uint64_t seed = 0;
  int parts = 0;                                     // learn
  std::vector<std::string> sensors;                  // learn, object, calibrate stripe
  std::vector<double> cube{120.0, 12.0}, cube_pose;  // calibrate stripe, pantilt
  std::string target = "stripe";                     // calibrate: stripe | pantilt | css
  std::optional<double> tilt_rad;                    // calibrate pantilt: the held tilt
  double sphere_radius_mm = 0;                       // calibrate css
  std::vector<double> robot_pose;                    // calibrate css: X,Y,Z,ROLL,PITCH,YAW
  std::vector<std::string> scans;                    // calibrate: earlier request ids to join
};

Eigen::Vector3d vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

std::string make_id() {
  std::random_device rd;
  return "req-" + std::to_string(rd() % 1000000);
}

int run(RequestArgs& a, daemon::DetectKind kind) {
  daemon::ScanRequest req;
  req.id = a.id.empty() ? make_id() : a.id;
  req.kind = kind;
  req.model = a.model;
  req.sensor = a.sensor;
  req.sensors = a.sensors;
  req.bore.position_mm = {a.position_mm[0], a.position_mm[1], a.position_mm[2]};
  req.bore.axis = {a.axis[0], a.axis[1], a.axis[2]};
  req.bore.radius_mm = a.radius_mm;
  req.sweep_start = a.sweep[0];
  req.sweep_end = a.sweep[1];
  req.sweep_speed = a.sweep[2];
  if (a.plane_normal.size() == 3) req.bore.plane_normal = vec3(a.plane_normal);
  req.bore.outer_radius_mm = a.outer_radius_mm;
  req.bore.walls = a.walls;
  req.bore.normal_keep = a.normal_keep;
  req.bore.half_angle_rad = a.half_angle;
  req.bore.cylinder_radius_mm = a.cylinder_radius_mm;
  req.bore.radius2_mm = a.radius2_mm;
  if (a.major_axis.size() == 3) req.bore.major_axis = vec3(a.major_axis);
  if (a.view_dir.size() == 3) req.view_dir = vec3(a.view_dir);
  if (a.sensor_position.size() == 3) req.sensor_position = vec3(a.sensor_position);
  req.instances = a.instances;
  req.hypotheses = a.hypotheses;
  req.trials = a.trials;
  req.seed = a.seed;
  req.parts = a.parts;
  if (kind == daemon::DetectKind::kCalibrate && a.target == "css") {
    req.target.kind = "css";
    req.target.radius_mm = a.sphere_radius_mm;
    const std::vector<double>& v = a.robot_pose;
    req.target.T_base_joint = hal::pose_xyz_rpy(v[0], v[1], v[2], v[3], v[4], v[5]);
    req.target.scans = a.scans;
  } else if (kind == daemon::DetectKind::kCalibrate) {  // the cube: stripe or pantilt
    req.target.kind = a.target;
    req.target.edge_mm = a.cube[0];
    req.target.bar_mm = a.cube[1];
    const std::vector<double>& v = a.cube_pose;
    req.target.T_table_target = hal::pose_xyz_rpy(v[0], v[1], v[2], v[3], v[4], v[5]);
    req.target.tilt_rad = a.tilt_rad;  // pantilt only; unset for stripe
    req.target.scans = a.scans;
  }
  try {
    const std::uint32_t domain = a.domain ? *a.domain : daemon::ros_domain_id().value_or(0);
    daemon::DdsClient client(domain);
    const auto timeout = std::chrono::milliseconds(std::llround(a.timeout_s * 1000));
    // Discovery may take a while when many clients start at once: the whole timeout is
    // available for it, and the result's own wait starts once the daemon is matched.
    if (!client.wait_for_daemon(timeout)) {
      std::cerr << "rangefit request: no rangefitd on DDS domain " << domain << " within "
                << a.timeout_s << " s\n";
      return kExitBadInput;
    }
    client.send(req, a.linear);
    const auto result = client.wait_result(req.id, timeout);
    if (!result) {
      std::cerr << "rangefit request: no result for " << req.id << " within " << a.timeout_s
                << " s\n";
      return kExitBadInput;
    }
    std::cout << daemon::to_json(*result).dump(2) << "\n";
    return daemon::exit_code_of(*result);
  } catch (const std::exception& e) {
    std::cerr << "rangefit request: " << e.what() << "\n";
    return kExitBadInput;
  }
}

void common(CLI::App* sub, RequestArgs& a) {
  sub->add_option("--domain", a.domain,
                  "DDS domain id of rangefitd (default: ROS_DOMAIN_ID, else 0)")
      ->check(CLI::Range(0, 232));
  sub->add_option("--id", a.id, "request id (default: random)");
  sub->add_option("--sensor", a.sensor, "device name (default: the daemon's default for the kind)");
  sub->add_option("--sweep", a.sweep, "sweep start end speed (mm or rad, per second)");
  sub->add_flag("--linear", a.linear, "the sensor sweeps linearly (values in mm)");
  sub->add_option("--timeout", a.timeout_s, "seconds to wait for the daemon and for the result")
      ->capture_default_str()
      ->check(finite_range(0.001, 86400.0));
  sub->add_option("--seed", a.seed, "seed of the detection (default: the daemon's)");
}

// `rangefit request bore`: the CAD prior of `rangefit bore`, sent to the daemon.
void add_bore_request(CLI::App* cmd, int* exit_code) {
  static RequestArgs bore_args;
  auto* bore = cmd->add_subcommand("bore", "find a bore near a CAD prior");
  common(bore, bore_args);
  // The names of `rangefit bore` (--cad-*) are accepted beside the short ones; vectors as
  // X,Y,Z or X Y Z.
  bore->add_option("--position,--cad-entrance", bore_args.position_mm,
                   "expected entrance x y z, mm (world)")
      ->required()
      ->delimiter(',');
  bore->add_option("--axis,--cad-axis", bore_args.axis, "expected axis x y z")
      ->capture_default_str()
      ->delimiter(',');
  bore->add_option("--radius,--cad-radius", bore_args.radius_mm, "expected radius, mm")
      ->required()
      ->check(finite_range(1e-3, 1e5));
  add_vector_option(bore, "--plane-normal,--cad-plane-normal", bore_args.plane_normal,
                    "normal x y z of the surface around the bore (default: the axis)");
  bore->add_option("--outer-radius,--cad-outer-radius", bore_args.outer_radius_mm,
                   "a thick-walled pipe's outer wall radius, mm (the bore is its inner wall)")
      ->check(finite_range(1e-3, 1e5));
  bore->add_option("--walls", bore_args.walls,
                   "which wall of a pipe to fit: inner (the bore, default), outer "
                   "(--cad-outer-radius, else --cad-radius) or both (the outer one as \"outer\")")
      ->check(CLI::IsMember({"inner", "outer", "both"}));
  add_vector_option(bore, "--view-dir", bore_args.view_dir,
                    "direction x y z from the part toward the sensor (default: what the "
                    "sensor reports)")
      ->check(finite_range(-kMaxCoordinateMm, kMaxCoordinateMm));
  add_vector_option(bore, "--sensor-position", bore_args.sensor_position,
                    "sensor position x y z, mm, instead of --view-dir")
      ->check(finite_range(-kMaxCoordinateMm, kMaxCoordinateMm));
  bore->add_option("--normal-keep", bore_args.normal_keep,
                   "share (0..1] of region points that get a normal (thesis: 0.2)")
      ->check(finite_range(0.001, 1.0));
  bore->add_option("--cad-half-angle", bore_args.half_angle,
                   "a conical bore's half-angle, rad (a 90 deg countersink: 0.7854)")
      ->check(finite_range(0.0, 1.39));
  bore->add_option("--cad-cylinder-radius", bore_args.cylinder_radius_mm,
                   "with --cad-half-angle: the cylindrical bore the cone ends in, radius mm")
      ->check(finite_range(1e-3, 1e5));
  bore->add_option("--cad-radius2", bore_args.radius2_mm,
                   "an elliptic bore's semi-axis across --cad-major-axis, mm")
      ->check(finite_range(1e-3, 1e5));
  add_vector_option(bore, "--cad-major-axis", bore_args.major_axis,
                    "an elliptic bore: direction x y z of the --cad-radius semi-axis")
      ->check(finite_range(-kMaxCoordinateMm, kMaxCoordinateMm));
  bore->callback([exit_code] { *exit_code = run(bore_args, daemon::DetectKind::kBore); });
}

// `rangefit request object`: a configured model, as `rangefit object`.
void add_object_request(CLI::App* cmd, int* exit_code) {
  static RequestArgs object_args;
  auto* object = cmd->add_subcommand("object", "find a configured object model");
  common(object, object_args);
  object->add_option("--model", object_args.model, "object model name (daemon config)")->required();
  object->add_option("--instances", object_args.instances, "K: instances to report, best first")
      ->check(CLI::Range(1, 1000));
  object
      ->add_option("--hypotheses", object_args.hypotheses,
                   "m: pose hypotheses per part (default: the detector's)")
      ->check(CLI::Range(1, 10000));
  object->add_option("--trials", object_args.trials, "n: RANSAC trials per hypothesis")
      ->check(CLI::Range(1, 10000));
  add_vector_option(object, "--viewpoint", object_args.sensor_position,
                    "sensor position x y z, mm (default: what the sensor reports)")
      ->check(finite_range(-kMaxCoordinateMm, kMaxCoordinateMm));
  object
      ->add_option("--sensors", object_args.sensors,
                   "the two cameras of one laser plane (A,B: stripe or pan-tilt devices, each "
                   "its configured sweep): on one axis or head they sweep together, and the "
                   "object is found in both clouds fused, a point either camera saw counting")
      ->delimiter(',')
      ->excludes("--sensor")
      ->excludes("--sweep");
  object->callback([exit_code] { *exit_code = run(object_args, daemon::DetectKind::kObject); });
}

// `rangefit request learn`: scan and learn, as `rangefit learn`.
void add_learn_request(CLI::App* cmd, int* exit_code) {
  static RequestArgs learn_args;
  auto* learn = cmd->add_subcommand(
      "learn", "scan and learn an object model (as `rangefit learn`); model.toml in the spool");
  common(learn, learn_args);
  learn->add_option("--name", learn_args.model, "the model's name (default: learnt)");
  learn->add_option("--parts", learn_args.parts, "parts of the model: 1, or 2 (head and shaft)")
      ->check(CLI::Range(1, 2));
  learn
      ->add_option("--sensors", learn_args.sensors,
                   "scan with each of these devices (A,B; each its configured sweep) and learn "
                   "from their clouds fused, as `rangefit learn --cloud A --cloud B`")
      ->delimiter(',')
      ->excludes("--sensor")
      ->excludes("--sweep");
  learn->callback([exit_code] { *exit_code = run(learn_args, daemon::DetectKind::kLearn); });
}

// `rangefit request calibrate css`: one robot pose's scan of the sphere; the request that names
// the earlier poses' requests (--scans) also solves for the CSS mount on the last joint.
void add_calibrate_css_request(CLI::App* calibrate, int* exit_code) {
  static RequestArgs css_args;
  css_args.target = "css";
  auto* css = calibrate->add_subcommand(
      "css",
      "the CSS on the robot from sphere scans at several robot poses, one request per pose (as "
      "`rangefit calibrate css`)");
  common(css, css_args);
  css->add_option("--sphere-radius", css_args.sphere_radius_mm,
                  "certified radius of the reference sphere (mm)")
      ->required()
      ->check(finite_range(0.1, 1e4));
  css->add_option("--robot-pose", css_args.robot_pose,
                  "the last joint's frame in the robot base at this scan, as the robot "
                  "controller reports it: X,Y,Z,ROLL,PITCH,YAW (mm, rad)")
      ->required()
      ->expected(6)
      ->delimiter(',')
      ->check(finite_range(-kMaxCoordinateMm, kMaxCoordinateMm));
  css->add_option("--scans", css_args.scans,
                  "ids of the earlier css requests (other poses) to solve with this one: ID,ID,...")
      ->delimiter(',');
  css->callback([exit_code] { *exit_code = run(css_args, daemon::DetectKind::kCalibrate); });
}

// --cube and --cube-pose of the hollow cube's calibrate requests (stripe, pantilt); where: the
// frame the pose is in, as the help text names it.
void add_cube_options(CLI::App* sub, RequestArgs& a, const std::string& where) {
  sub->add_option("--cube", a.cube, "cube EDGE,BAR (mm)")
      ->expected(2)
      ->delimiter(',')
      ->check(finite_range(1.0, kMaxCoordinateMm));
  sub->add_option("--cube-pose", a.cube_pose,
                  "cube pose " + where + " X,Y,Z,ROLL,PITCH,YAW (mm, rad)")
      ->required()
      ->expected(6)
      ->delimiter(',')
      ->check(finite_range(-kMaxCoordinateMm, kMaxCoordinateMm));
}

// `rangefit request calibrate pantilt`: one pan sweep over the hollow cube at the tilt the cell
// program holds the head at; the request that names the earlier tilts' requests (--scans) also
// solves for the head.
void add_calibrate_pantilt_request(CLI::App* calibrate, int* exit_code) {
  static RequestArgs pantilt_args;
  pantilt_args.target = "pantilt";
  auto* pantilt = calibrate->add_subcommand(
      "pantilt",
      "the pan-tilt head from pan sweeps over the hollow cube at two or more tilts, one request "
      "per tilt (as `rangefit calibrate pantilt`)");
  common(pantilt, pantilt_args);
  add_cube_options(pantilt, pantilt_args, "in the head's world frame");
  pantilt
      ->add_option("--tilt", pantilt_args.tilt_rad,
                   "the tilt the cell program holds the head at for this sweep, as the head "
                   "reports it (rad; default: whatever the head reports)")
      ->check(finite_range(-std::numbers::pi / 2, std::numbers::pi / 2));
  pantilt
      ->add_option("--scans", pantilt_args.scans,
                   "ids of the earlier pantilt requests (other tilts) to solve with this one: "
                   "ID,ID,...")
      ->delimiter(',');
  pantilt->callback(
      [exit_code] { *exit_code = run(pantilt_args, daemon::DetectKind::kCalibrate); });
}

// `rangefit request calibrate stripe`: one sweep over the hollow cube; the request that names
// the other cameras' requests (--scans) solves for all of them.
void add_calibrate_request(CLI::App* cmd, int* exit_code) {
  static RequestArgs calibrate_args;
  auto* calibrate = cmd->add_subcommand(
      "calibrate", "scan a calibration body and calibrate; written to the spool, never applied");
  calibrate->require_subcommand(1);
  auto* stripe = calibrate->add_subcommand(
      "stripe",
      "the stripe cell from a sweep over the hollow cube, with one or all cameras of the laser "
      "plane (as `rangefit calibrate stripe`)");
  common(stripe, calibrate_args);
  add_cube_options(stripe, calibrate_args, "on the table");
  stripe
      ->add_option("--sensors", calibrate_args.sensors,
                   "the cameras of the laser plane to calibrate together (A,B: stripe devices): "
                   "on one axis they sweep the cube together, the axis moving once")
      ->delimiter(',')
      ->excludes("--sensor")
      ->excludes("--sweep");
  stripe
      ->add_option("--scans", calibrate_args.scans,
                   "ids of the earlier stripe requests (the laser plane's other cameras, each "
                   "its own --sensor) to solve with this one: ID,ID,...")
      ->delimiter(',');
  stripe->callback(
      [exit_code] { *exit_code = run(calibrate_args, daemon::DetectKind::kCalibrate); });
  add_calibrate_pantilt_request(calibrate, exit_code);
  add_calibrate_css_request(calibrate, exit_code);
}

}  // namespace

void add_request_command(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("request", "ask a running rangefitd to scan and detect (DDS)");
  cmd->require_subcommand(1);
  add_bore_request(cmd, exit_code);
  add_object_request(cmd, exit_code);
  add_learn_request(cmd, exit_code);
  add_calibrate_request(cmd, exit_code);
}

}  // namespace rangefit::cli
