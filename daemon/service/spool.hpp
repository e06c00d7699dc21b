#pragma once
// The spool: every scan's cloud and result are written here before the result is published, so
// nothing is lost and a failed detection can be replayed offline (`rangefit replay ENTRY`).
// One directory per scan: request.json, cloud.ply (binary, world frame, mm), result.json, and
// picture.png (the scan with the detection drawn over it) when a picture writer is set.
// Entries are written under a temporary name and renamed, so a reader never sees half of one.
// Bounded by total size and by age; the oldest entries go first.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "daemon/service/config.hpp"
#include "daemon/service/scan_types.hpp"
#include "detect/common/point_cloud.hpp"

namespace rangefit::daemon {

struct SpoolEntry {
  ScanRequest request;
  PointCloud cloud;
  DetectionResult result;
};

class Spool {
 public:
  explicit Spool(SpoolConfig config);

  // Draws an entry's picture.png; false and *error when it cannot (the entry is kept without).
  using PictureWriter = std::function<bool(const std::filesystem::path&, const PointCloud&,
                                           const DetectionResult&, std::string*)>;
  // Called by write() for every entry with points while config.pictures is set.
  void set_picture(PictureWriter writer) { picture_ = std::move(writer); }

  // Creates the directory if needed; false + *error when it cannot be created or written.
  bool open(std::string* error);

  // Writes one entry and sets result.spool_entry to its path; then prunes. Returns false and
  // sets *error on I/O failure (the caller still publishes the result, with the error noted).
  bool write(const ScanRequest& request, const PointCloud& cloud, DetectionResult& result,
             std::string* error);

  // Removes entries older than max_age, then the oldest until the total fits max_bytes.
  // Returns the number removed.
  std::size_t prune(
      std::filesystem::file_time_type now = std::filesystem::file_time_type::clock::now());

  std::uint64_t total_bytes() const;
  std::size_t entry_count() const;
  const std::filesystem::path& directory() const { return config_.directory; }

 private:
  SpoolConfig config_;
  std::uint64_t sequence_ = 0;
  PictureWriter picture_;
};

// Reads an entry written by Spool::write. nullopt + *error when missing or malformed.
std::optional<SpoolEntry> read_spool_entry(const std::filesystem::path& entry, std::string* error);

}  // namespace rangefit::daemon
