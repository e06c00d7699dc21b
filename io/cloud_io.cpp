#include "io/cloud_io.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "io/pcd.hpp"
#include "io/ply.hpp"

namespace rangefit::io {
namespace {

enum class Format { kPly, kPcd };

Format format_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".ply") return Format::kPly;
  if (ext == ".pcd") return Format::kPcd;
  throw IoError(path, "unknown point-cloud extension '" + path.extension().string() +
                          "' (expected .ply or .pcd)");
}

}  // namespace

PointCloud read_cloud(const std::filesystem::path& path, CloudReadReport* report) {
  return format_of(path) == Format::kPly ? read_ply(path, report) : read_pcd(path, report);
}

void write_cloud(const std::filesystem::path& path, const PointCloud& cloud) {
  if (format_of(path) == Format::kPly) {
    write_ply(path, cloud);
  } else {
    write_pcd(path, cloud);
  }
}

}  // namespace rangefit::io
