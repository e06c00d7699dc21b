// Writes the io test fixtures with rangefit's writers in every binary variant, plus the values
// they hold as JSON, for test/io/check_cloud_files.py: an independent reader (Python's struct)
// that checks what other tools will find in rangefit's files.
//   write_fixture_clouds DIR
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "io/pcd.hpp"
#include "io/ply.hpp"
#include "io/text_number.hpp"
#include "test/io/cloud_fixtures.hpp"

namespace {

using namespace rangefit;
using io::detail::number_text;

std::string vec(const Eigen::Vector3d& v) {
  std::string out = "[";
  for (int a = 0; a < 3; ++a) {
    if (a > 0) out += ", ";
    out += number_text(v[a]);
  }
  return out += "]";
}

// {"frame_id":..., "rows":R, "cols":C, "index":[...], "points":[[x,y,z],...], ...}
std::string to_json(const PointCloud& cloud) {
  std::string out = "{\"frame_id\": \"" + cloud.frame_id +
                    "\", \"rows\": " + std::to_string(cloud.grid.rows) +
                    ", \"cols\": " + std::to_string(cloud.grid.cols) + ", \"index\": [";
  auto list = [&](std::size_t n, const auto& item) {
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0) out += ", ";
      out += item(i);
    }
  };
  list(cloud.grid.index.size(), [&](std::size_t i) { return std::to_string(cloud.grid.index[i]); });
  out += "], \"points\": [";
  list(cloud.size(), [&](std::size_t i) { return vec(cloud.points[i]); });
  out += "], \"normals\": [";
  list(cloud.normals.size(), [&](std::size_t i) { return vec(cloud.normals[i]); });
  out += "], \"stamps_ns\": [";
  list(cloud.stamps.size(), [&](std::size_t i) { return std::to_string(cloud.stamps[i].count()); });
  return out + "]}";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: write_fixture_clouds DIR\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  PointCloud plain;
  plain.frame_id = "world";
  plain.points = {{1, 2, 3}, {-4.25, 5e-7, 6e8}, {0.1, -0.2, 1000.0 / 3.0}};
  const PointCloud organised = io::test::organised_cloud();
  try {
    for (const auto& [name, cloud] :
         {std::pair{"plain", plain}, std::pair{"organised", organised}}) {
      const std::string base = (dir / name).string();
      io::write_ply(base + ".ply", cloud);  // the defaults: binary little endian, float
      io::write_ply(base + "_be.ply", cloud, io::PlyEncoding::kBinaryBigEndian);
      io::write_ply(base + "_double.ply", cloud, io::PlyEncoding::kBinaryLittleEndian,
                    io::Precision::kFloat64);
      io::write_pcd(base + ".pcd", cloud);  // binary, float
      io::write_pcd(base + "_double.pcd", cloud, io::PcdEncoding::kBinary, io::Precision::kFloat64);
      std::ofstream(base + ".json") << to_json(cloud) << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
