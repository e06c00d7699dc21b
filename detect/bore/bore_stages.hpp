#pragma once
// The stages of detect_bore (thesis 4.1.1-4.1.4), each a function of the previous stages'
// values: the CAD prior as a frame, the region of interest, the normals, the Gaussian-image
// segmentation with the entrance plane, and per wall the sequential cylinder fit with the notch
// re-fit, the refinement and the entrance. Internal to detect/ (the API is bore_detector.hpp).
// Every buffer of a stage comes from the call's arena (`mr`, see bore_workspace.hpp).

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <memory_resource>
#include <vector>

#include "detect/bore/bore_options.hpp"
#include "detect/bore/bore_refine.hpp"
#include "detect/bore/bore_region.hpp"
#include "detect/bore/bore_result.hpp"
#include "detect/bore/bore_surface.hpp"
#include "detect/bore/cylinder_rsf.hpp"
#include "detect/common/normals.hpp"
#include "detect/common/pca.hpp"
#include "detect/common/point_cloud.hpp"

namespace rangefit::bore {

// Milliseconds per stage, read off one steady clock.
class StageClock {
 public:
  StageClock() : start_(Clock::now()), last_(start_) {}
  double lap();          // since the previous lap (or the start)
  double total() const;  // since the start
 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_, last_;
};

// One cylinder to fit: its CAD radius, which side of it faces the axis, and the band of
// distances from the CAD axis its wall points may have (radius clustering: a pipe's other wall
// lies outside the band, half the wall thickness away).
struct WallTarget {
  double radius = 0.0;
  bool inner = true;  // concave bore wall (faces the axis); false: a pipe's convex outer wall
  double rho_lo = 0.0, rho_hi = 0.0;
};

// The CAD prior as every stage uses it: directions toward the sensor, the walls to fit and the
// sizes that follow from them.
struct BoreFrame {
  explicit BoreFrame(std::pmr::memory_resource* mr = std::pmr::get_default_resource())
      : targets(mr) {}
  Eigen::Vector3d entrance = Eigen::Vector3d::Zero();
  Eigen::Vector3d view = Eigen::Vector3d::UnitZ();   // unit, toward the sensor
  Eigen::Vector3d n_cad = Eigen::Vector3d::UnitZ();  // CAD plane normal, toward the sensor
  Eigen::Vector3d a_cad = Eigen::Vector3d::UnitZ();  // CAD axis, toward the sensor
  std::pmr::vector<WallTarget> targets;              // inner first (unless walls = kOuter)
  double r_min = 0.0, r_max = 0.0;                   // smallest and largest target radius
  double normal_radius = 0.0;                        // R before the density adjustment, mm
  double roi_radius = 0.0;                           // mm
};

// False for NaN/Inf or zero-length prior values, radius <= 0, bad options (kBadPrior).
bool valid_input(const BorePrior& prior, const BoreOptions& o);
BoreFrame bore_frame(const BorePrior& prior, const BoreOptions& o, std::pmr::memory_resource* mr);

// 4.1.1 region of interest, read within the region budget when cost-bounded.
BoreRegion region_of_interest(const PointCloud& cloud, const BoreFrame& f, const BoreOptions& o,
                              std::pmr::memory_resource* mr);

// 4.1.1 normals on the (sub-sampled) region, neighbours from every point read.
struct RegionNormals {
  explicit RegionNormals(std::pmr::memory_resource* mr) : queries(mr), normals{std::pmr::vector<Eigen::Vector3d>(mr)} {}
  std::pmr::vector<std::uint32_t> queries;  // into region.points
  NormalEstimate normals;              // one per query
  double radius = 0.0;                 // R used, mm
};
RegionNormals region_normals(const BoreRegion& region, const BoreFrame& f, const BoreOptions& o,
                             std::pmr::memory_resource* mr);

// 4.1.2 Gaussian-image segmentation with the CAD prior (eq. 4.5, 4.6).
struct Wall {
  explicit Wall(std::pmr::memory_resource* mr) : points(mr), normals(mr), bottom(mr) {}
  std::pmr::vector<Eigen::Vector3d> points, normals;  // normals turned toward the axis
  std::pmr::vector<Eigen::Vector3d> bottom;  // points facing along the axis inside the bore
};
struct Segmentation {
  explicit Segmentation(std::pmr::memory_resource* mr) : plane(mr), walls(mr) {}
  std::pmr::vector<Eigen::Vector3d> plane;  // entrance-plane points
  std::pmr::vector<Wall> walls;             // one per target
};
Segmentation segment(const BoreRegion& region, const RegionNormals& n, const BoreFrame& f,
                     const BorePrior& prior, const BoreOptions& o, std::pmr::memory_resource* mr);

// 4.1.2 the entrance plane of the plane points (invalid: too few, or no plane).
pca::Plane entrance_plane(const BoreRegion& region, const Segmentation& s, const BoreFrame& f,
                          const BoreOptions& o, std::pmr::memory_resource* mr);

// 4.1.3-4.1.4 for one wall.
struct WallFit {
  BoreReason reason = BoreReason::kFitFailed;
  Cylinder cylinder;
  RsfResult rsf;
  bool second_fit = false, refined = false;
  std::size_t wall_final = 0, refine_inliers = 0;
  CylinderSigma sigma;  // of the refined cylinder (invalid: not refined)
  Eigen::Vector3d entrance = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::UnitZ();
};
// base: the refinement's inputs shared by the walls (cloud, region, plane, up, R, arena).
WallFit fit_wall(const RefineInput& base, const Wall& wall, const WallTarget& target,
                 const BoreFrame& f, const BorePrior& prior, const BoreOptions& o,
                 StageClock& clock, BoreTimes& times);

// Beyond the thesis: a cone or elliptic bore (BorePrior::half_angle or radius2).
bool has_shape(const BorePrior& prior);
// False for a bad model (kBadShape): see to_string(BoreReason::kBadShape).
bool valid_shape(const BorePrior& prior, const BoreOptions& o);
// The wall's model, seeded by the RSF cylinder of the segmented wall where it has one that
// agrees with the CAD axis (a countersink's cylinder, a taper of less than eq. 4.6's 5 deg, an
// ellipse), else by the CAD axis, then fitted on the region's points near it where it faces the
// sensor (BoreOptions::view_dir or sensor_position; an ellipse without either: the side its
// segmented wall was seen from) and polished on the full-resolution points within 3 robust
// sigmas (detect/bore_surface.hpp).
struct ShapeWallFit {
  BoreReason reason = BoreReason::kShapeFitFailed;
  SurfaceFitResult fit;
  RsfResult rsf;
  bool seeded_by_rsf = false;
};
ShapeWallFit fit_shaped_wall(const RefineInput& base, const Wall& wall, const BoreFrame& f,
                             const BorePrior& prior, const BoreOptions& o);

}  // namespace rangefit::bore
