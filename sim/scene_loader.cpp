#include "sim/scene_loader.hpp"

#include <toml++/toml.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "io/stl.hpp"
#include "sim/bore_plate_mesh.hpp"

namespace rangefit::sim {
namespace {

using Eigen::Vector3d;
constexpr double kDeg = std::numbers::pi / 180.0;

// Where we are while reading: file, the table being read and its label for messages.
struct Ctx {
  const std::string& file;
  const toml::table& table;
  std::string label;  // e.g. "object 'table'"

  [[noreturn]] void fail(std::string_view field, const std::string& what) const {
    const toml::node* node = table.get(field);
    const auto& src = node ? node->source() : table.source();
    std::ostringstream msg;
    msg << file << ":" << src.begin.line << ": " << label << ": field '" << field << "' " << what;
    throw SceneError(msg.str());
  }

  bool has(std::string_view field) const { return table.contains(field); }

  double number(std::string_view field, std::optional<double> fallback = std::nullopt) const {
    const toml::node* node = table.get(field);
    if (!node) {
      if (fallback) return *fallback;
      fail(field, "is missing");
    }
    const auto v = node->value<double>();
    if (!v || !std::isfinite(*v)) fail(field, "must be a finite number");
    return *v;
  }

  double positive(std::string_view field, std::optional<double> fallback = std::nullopt) const {
    const double v = number(field, fallback);
    if (!(v > 0.0)) fail(field, "must be positive");
    return v;
  }

  template <int N>
  Eigen::Matrix<double, N, 1> vec(std::string_view field,
                                  std::optional<Eigen::Matrix<double, N, 1>> fallback = {}) const {
    const toml::node* node = table.get(field);
    if (!node) {
      if (fallback) return *fallback;
      fail(field, "is missing");
    }
    const toml::array* arr = node->as_array();
    if (!arr || arr->size() != N)
      fail(field, "must be an array of " + std::to_string(N) + " numbers");
    Eigen::Matrix<double, N, 1> out;
    for (int i = 0; i < N; ++i) {
      const auto v = (*arr)[static_cast<std::size_t>(i)].value<double>();
      if (!v || !std::isfinite(*v))
        fail(field, "must be an array of " + std::to_string(N) + " numbers");
      out[i] = *v;
    }
    return out;
  }

  std::string text(std::string_view field, std::optional<std::string> fallback = {}) const {
    const toml::node* node = table.get(field);
    if (!node) {
      if (fallback) return *fallback;
      fail(field, "is missing");
    }
    const auto v = node->value<std::string>();
    if (!v) fail(field, "must be a string");
    return *v;
  }
};

Eigen::Isometry3d read_pose(const Ctx& c) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = c.vec<3>("position", Vector3d::Zero());
  if (c.has("rpy_deg") && c.has("z_axis")) c.fail("z_axis", "cannot be combined with rpy_deg");
  if (c.has("z_axis")) {
    const Vector3d z = c.vec<3>("z_axis");
    if (z.norm() < 1e-9) c.fail("z_axis", "must not be the zero vector");
    T.linear() =
        Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), z.normalized()).toRotationMatrix();
  } else {
    const Vector3d rpy = kDeg * c.vec<3>("rpy_deg", Vector3d::Zero());
    T.linear() = (Eigen::AngleAxisd(rpy.z(), Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(rpy.y(), Vector3d::UnitY()) *
                  Eigen::AngleAxisd(rpy.x(), Vector3d::UnitX()))
                     .toRotationMatrix();
  }
  return T;
}

BoreSpec read_bore(const Ctx& c) {
  BoreSpec b;
  b.name = c.text("name");
  if (!parse_bore_kind(c.text("kind", "straight"), b.kind)) {
    c.fail("kind", "must be straight, slanted, chamfered, rounded or notched");
  }
  b.diameter_mm = c.positive("diameter");
  b.slant_rad = kDeg * c.number("slant_deg", b.kind == BoreKind::kSlanted ? 45.0 : 0.0);
  b.edge_mm = c.positive("edge", 1.0);
  b.notches = static_cast<int>(c.positive("notches", 6.0));
  b.notch_depth_mm = c.positive("notch_depth", 2.0);
  b.notch_width_rad = kDeg * c.positive("notch_width_deg", 12.0);
  return b;
}

void read_object(const Ctx& c, const std::string& base_dir, Scene& scene) {
  SceneObject obj;
  obj.name = c.text("name");
  const std::string type = c.text("type");
  Ctx named{c.file, c.table, "object '" + obj.name + "'"};
  obj.T_world_object = read_pose(named);
  if (type == "plane") {
    const Eigen::Vector2d s = named.vec<2>("size", Eigen::Vector2d(1000.0, 1000.0));
    if (!(s.minCoeff() > 0.0)) named.fail("size", "must be positive");
    obj.shape = PlaneShape{s.x(), s.y()};
  } else if (type == "box") {
    const Vector3d s = named.vec<3>("size");
    if (!(s.minCoeff() > 0.0)) named.fail("size", "must be positive");
    obj.shape = BoxShape{s};
  } else if (type == "cylinder") {
    obj.shape = CylinderShape{named.positive("radius"), named.positive("height")};
  } else if (type == "sphere") {
    obj.shape = SphereShape{named.positive("radius")};
  } else if (type == "superquadric") {
    const Vector3d a = named.vec<3>("a");
    const Eigen::Vector2d e = named.vec<2>("eps", Eigen::Vector2d(1.0, 1.0));
    const Eigen::Vector2d k = named.vec<2>("taper", Eigen::Vector2d(0.0, 0.0));
    if (!(a.minCoeff() > 0.0)) named.fail("a", "must be positive");
    if (!(e.minCoeff() >= 0.1 && e.maxCoeff() <= 2.0)) named.fail("eps", "must lie in [0.1, 2]");
    if (!(k.cwiseAbs().maxCoeff() <= 1.0)) named.fail("taper", "must lie in [-1, 1]");
    obj.shape = SuperquadricShape{Superquadric{a.x(), a.y(), a.z(), e.x(), e.y(), k.x(), k.y()}};
  } else if (type == "mesh") {
    const std::string file = named.text("file");
    const std::filesystem::path path = std::filesystem::path(base_dir) / file;
    try {
      obj.shape = MeshShape{io::read_stl(path), file};
    } catch (const std::exception& e) {
      named.fail("file", std::string("cannot be loaded: ") + e.what());
    }
  } else if (type == "bore_plate") {
    BorePlateSpec spec;
    spec.cell_mm = named.positive("cell", spec.cell_mm);
    spec.thickness_mm = named.positive("thickness", spec.thickness_mm);
    spec.segments = static_cast<int>(named.positive("segments", spec.segments));
    const toml::array* bores = c.table.get_as<toml::array>("bore");
    if (!bores) named.fail("bore", "is missing: a bore_plate needs [[object.bore]] tables");
    for (const toml::node& n : *bores) {
      const toml::table* t = n.as_table();
      if (!t) named.fail("bore", "must be an array of tables");
      spec.bores.push_back(read_bore(Ctx{c.file, *t, named.label + " bore"}));
    }
    BorePlate plate = make_bore_plate(spec);
    if (!plate.error.empty()) named.fail("bore", "is invalid: " + plate.error);
    for (BoreTruth b : plate.bores) {
      b.opening_mm = obj.T_world_object * b.opening_mm;
      b.axis = obj.T_world_object.linear() * b.axis;
      scene.bores.push_back(b);
    }
    obj.shape = MeshShape{std::move(plate.mesh), "bore_plate"};
  } else {
    named.fail("type", "must be plane, box, cylinder, sphere, superquadric, mesh or bore_plate");
  }
  scene.objects.push_back(std::move(obj));
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name, const std::string& base_dir) {
  toml::table root;
  try {
    root = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << name << ":" << e.source().begin.line << ": " << e.description();
    throw SceneError(msg.str());
  }
  Scene scene;
  scene.source = name;
  const Ctx top{name, root, "scene"};
  const toml::array* objects = root.get_as<toml::array>("object");
  if (!objects) top.fail("object", "is missing: a scene needs at least one [[object]]");
  for (const toml::node& n : *objects) {
    const toml::table* t = n.as_table();
    if (!t) top.fail("object", "must be an array of tables");
    read_object(Ctx{name, *t, "object"}, base_dir, scene);
  }
  // Ground truth of bores in mesh objects (a bore_plate object gives its own).
  if (const toml::array* bores = root.get_as<toml::array>("bore")) {
    for (const toml::node& n : *bores) {
      const toml::table* t = n.as_table();
      if (!t) top.fail("bore", "must be an array of tables");
      const Ctx c{name, *t, "bore"};
      BoreTruth b;
      b.name = c.text("name");
      b.kind = c.text("kind", "straight");
      BoreKind kind;
      if (!parse_bore_kind(b.kind, kind)) {
        c.fail("kind", "must be straight, slanted, chamfered, rounded or notched");
      }
      b.diameter_mm = c.positive("diameter");
      b.opening_mm = c.vec<3>("opening");
      const Vector3d axis = c.vec<3>("axis");
      if (axis.norm() < 1e-9) c.fail("axis", "must not be the zero vector");
      b.axis = axis.normalized();
      scene.bores.push_back(b);
    }
  }
  if (const toml::table* sensors = root.get_as<toml::table>("sensors")) {
    const std::pair<const char*, Eigen::Isometry3d*> mounts[] = {
        {"css", &scene.mounts.T_scene_css},
        {"stripe", &scene.mounts.T_scene_stripe},
        {"pantilt", &scene.mounts.T_scene_pantilt}};
    for (const auto& [key, pose] : mounts) {
      if (const toml::table* t = sensors->get_as<toml::table>(key)) {
        *pose = read_pose(Ctx{name, *t, std::string("sensors.") + key});
      }
    }
  }
  return scene;
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace rangefit::sim
