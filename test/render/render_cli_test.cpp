// `rangefit render` and `rangefit bore|object --png` as a user runs them: a picture from a scan
// and a result JSON, and clear failures for results it cannot draw.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "io/cloud_io.hpp"
#include "test/support/synthetic_bore.hpp"

#ifdef RANGEFIT_CLI_PATH
namespace rangefit {
namespace render_cli_test {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

CliRun run(const std::string& args) {
  CliRun r;
  const std::string command = std::string(RANGEFIT_CLI_PATH) + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  char buffer[4096];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe))
    r.output.append(buffer, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

bool is_png(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  return in && std::string(magic + 1, 3) == "PNG";
}

class RenderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("rangefit_render_cli_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    sim::SyntheticBoreOptions o;
    o.radius = 5.0;
    o.spacing = 0.3;
    scan_ = sim::make_synthetic_bore(o);
    io::write_cloud(dir_ / "scan.ply", scan_.cloud);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string bore_args() const {
    const auto& t = scan_.truth;
    std::ostringstream s;
    s << "bore --cloud " << (dir_ / "scan.ply") << " --cad-entrance " << t.entrance.x() << ","
      << t.entrance.y() << "," << t.entrance.z() << " --cad-axis " << t.axis.x() << ","
      << t.axis.y() << "," << t.axis.z() << " --cad-radius 5";
    return s.str();
  }

  fs::path dir_;
  sim::SyntheticBoreScan scan_;
};

TEST_F(RenderCli, BorePngAndRenderOfItsJson) {
  const CliRun bore = run(bore_args() + " --json --png " + (dir_ / "bore.png").string() + " > " +
                          (dir_ / "bore.json").string());
  ASSERT_EQ(bore.exit_code, 0) << bore.output;
  EXPECT_TRUE(is_png(dir_ / "bore.png"));
  const CliRun render =
      run("render --cloud " + (dir_ / "scan.ply").string() + " --result " +
          (dir_ / "bore.json").string() + " --out " + (dir_ / "render.png").string());
  EXPECT_EQ(render.exit_code, 0) << render.output;
  EXPECT_TRUE(is_png(dir_ / "render.png"));
  // A scan alone is a picture too.
  EXPECT_EQ(run("render --cloud " + (dir_ / "scan.ply").string() + " --out " +
                (dir_ / "scan.png").string())
                .exit_code,
            0);
  EXPECT_TRUE(is_png(dir_ / "scan.png"));
}

TEST_F(RenderCli, ResultsItCannotDrawAreBadInput) {
  const std::string base = "render --cloud " + (dir_ / "scan.ply").string() + " --out " +
                           (dir_ / "x.png").string() + " --result ";
  std::ofstream(dir_ / "garbage.json") << "{ not json";
  CliRun r = run(base + (dir_ / "garbage.json").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("rangefit render:"), std::string::npos) << r.output;

  std::ofstream(dir_ / "other.json") << R"({"hello": 1})";
  r = run(base + (dir_ / "other.json").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("not a result"), std::string::npos) << r.output;

  // An object result needs the model file for the parts' shapes.
  std::ofstream(dir_ / "object.json")
      << R"({"object": "cylinder", "found": true, "reason": "found", "instances": [{"parts": [)"
      << R"({"name": "cylinder", "center": [0, 0, 0], "quaternion": [1, 0, 0, 0]}]}]})";
  r = run(base + (dir_ / "object.json").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("--model"), std::string::npos) << r.output;
  r = run(base + (dir_ / "object.json").string() +
          " --model " RANGEFIT_SOURCE_DIR "/data/models/cylinder.toml");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "garbage.png"));

  // rangefitd's result.json of a spool entry.
  const auto& t = scan_.truth;
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), t.axis);
  std::ofstream(dir_ / "spool.json")
      << R"({"request_id": "r1", "kind": "bore", "model": "", "found": true, "reason": "",)"
      << R"("parts": [{"name": "bore", "translation_mm": [)" << t.entrance.x() << ","
      << t.entrance.y() << "," << t.entrance.z() << R"(], "quaternion_wxyz": [)" << q.w() << ","
      << q.x() << "," << q.y() << "," << q.z() << R"(], "score": 1}], "bore_radius_mm": 5,)"
      << R"("num_points": 1, "scan_seconds": 1, "detect_seconds": 0.1, "spool_entry": ""})";
  fs::remove(dir_ / "x.png");
  r = run(base + (dir_ / "spool.json").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(is_png(dir_ / "x.png"));

  // A cone or ellipse result draws its shape; one no fit gives is bad input.
  const auto bore_json = [&](const std::string& shape) {
    std::ofstream(dir_ / "shape.json")
        << R"({"found": true, "entrance": [)" << t.entrance.x() << "," << t.entrance.y() << ","
        << t.entrance.z() << R"(], "axis": [)" << t.axis.x() << "," << t.axis.y() << ","
        << t.axis.z() << R"(], "radius": 5, )" << shape << "}";
    fs::remove(dir_ / "x.png");
    return run(base + (dir_ / "shape.json").string());
  };
  r = bore_json(R"("model": "ellipse", "radius2": 4.5, "major_axis": [1, 0, 0])");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(is_png(dir_ / "x.png"));
  r = bore_json(R"("model": "cone", "half_angle": 0.7854, "cylinder_radius": 3)");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = bore_json(R"("model": "ellipse", "radius2": -1, "major_axis": [1, 0, 0])");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("radius2"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));

  // A PNG that cannot be written fails the command.
  r = run(bore_args() + " --png " + (dir_ / "no" / "such" / "dir.png").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("--png"), std::string::npos) << r.output;
}

}  // namespace render_cli_test
}  // namespace rangefit
#endif
