#include "daemon/service/spool.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <system_error>
#include <vector>

#include "daemon/service/json_codec.hpp"
#include "io/ply.hpp"

namespace rangefit::daemon {
namespace fs = std::filesystem;
namespace {

constexpr const char* kTmpPrefix = ".tmp-";

std::string sanitise(const std::string& id) {
  std::string s;
  for (char c : id.substr(0, 48)) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '-' || c == '_';
    s.push_back(ok ? c : '_');
  }
  return s.empty() ? "unnamed" : s;
}

std::string utc_stamp() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%dT%H%M%SZ", &tm);
  return buf;
}

struct EntryInfo {
  fs::path path;
  fs::file_time_type time;
  std::uint64_t bytes = 0;
};

std::vector<EntryInfo> list_entries(const fs::path& dir) {
  std::vector<EntryInfo> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_directory(ec) || e.path().filename().string().starts_with(kTmpPrefix)) continue;
    EntryInfo info{e.path(), fs::last_write_time(e.path(), ec), 0};
    for (const auto& f : fs::directory_iterator(e.path(), ec)) {
      if (f.is_regular_file(ec)) info.bytes += f.file_size(ec);
    }
    out.push_back(std::move(info));
  }
  // Oldest first; names start with a UTC stamp and a sequence number, which breaks ties.
  std::sort(out.begin(), out.end(), [](const EntryInfo& a, const EntryInfo& b) {
    return a.time != b.time ? a.time < b.time : a.path.filename() < b.path.filename();
  });
  return out;
}

bool write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.flush();
  return static_cast<bool>(out);
}

}  // namespace

Spool::Spool(SpoolConfig config) : config_(std::move(config)) {}

bool Spool::open(std::string* error) {
  std::error_code ec;
  fs::create_directories(config_.directory, ec);
  if (ec) {
    *error = "spool " + config_.directory.string() + ": " + ec.message();
    return false;
  }
  // Left-overs of a crash in the middle of a write are incomplete by construction.
  for (const auto& e : fs::directory_iterator(config_.directory, ec)) {
    if (e.path().filename().string().starts_with(kTmpPrefix)) fs::remove_all(e.path(), ec);
  }
  return true;
}

bool Spool::write(const ScanRequest& request, const PointCloud& cloud, DetectionResult& result,
                  std::string* error) {
  // A new Spool on the same folder (a reload) starts its sequence again: within the same second
  // the same request id would name an entry that exists, so the sequence moves past it.
  std::string name;
  std::error_code exists_ec;
  do {
    char seq[16];
    std::snprintf(seq, sizeof seq, "%06llu",
                  static_cast<unsigned long long>(++sequence_ % 1000000));
    name = utc_stamp() + "-" + seq + "-" + sanitise(request.id);
  } while (fs::exists(config_.directory / name, exists_ec));
  const fs::path tmp = config_.directory / (kTmpPrefix + name);
  const fs::path final_path = config_.directory / name;
  result.spool_entry = final_path.string();
  std::error_code ec;
  try {
    fs::create_directories(tmp);
    // Doubles: a replay must see the very cloud the detectors saw.
    io::write_ply(tmp / "cloud.ply", cloud, io::PlyEncoding::kBinaryLittleEndian,
                  io::Precision::kFloat64);
    // What the request made besides the result (a learnt model, a calibration and its report),
    // named in the result by where they are once the entry is in place.
    for (const auto& [file, text] : result.files) {
      if (file.empty() || file.find('/') != std::string::npos || file.starts_with(".") ||
          !write_text(tmp / file, text)) {
        throw std::runtime_error("cannot write " + file);
      }
      if (!result.details.is_object()) result.details = nlohmann::json::object();
      result.details["files"][file] = (final_path / file).string();
    }
    if (!write_text(tmp / "request.json", to_json(request).dump(2)) ||
        !write_text(tmp / "result.json", to_json(result).dump(2))) {
      throw std::runtime_error("cannot write json");
    }
    std::string why;
    if (config_.pictures && picture_ && !cloud.empty() &&
        !picture_(tmp / "picture.png", cloud, result, &why)) {
      spdlog::warn("spool {}: no picture: {}", name, why);
    }
    fs::rename(tmp, final_path);
  } catch (const std::exception& e) {
    fs::remove_all(tmp, ec);
    result.spool_entry.clear();
    if (result.details.is_object()) result.details.erase("files");
    *error = "spool write " + final_path.string() + ": " + e.what();
    return false;
  }
  prune();
  return true;
}

std::size_t Spool::prune(fs::file_time_type now) {
  auto entries = list_entries(config_.directory);
  const auto max_age = std::chrono::duration_cast<fs::file_time_type::duration>(
      std::chrono::duration<double, std::ratio<3600>>(config_.max_age_hours));
  std::uint64_t total = 0;
  for (const auto& e : entries) total += e.bytes;
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& e : entries) {
    const bool too_old = now - e.time > max_age;
    const bool too_big = total > config_.max_bytes;
    if (!too_old && !too_big) break;  // sorted oldest first: the rest are younger
    fs::remove_all(e.path, ec);
    total -= e.bytes;
    ++removed;
  }
  return removed;
}

std::uint64_t Spool::total_bytes() const {
  std::uint64_t total = 0;
  for (const auto& e : list_entries(config_.directory)) total += e.bytes;
  return total;
}

std::size_t Spool::entry_count() const { return list_entries(config_.directory).size(); }

std::optional<SpoolEntry> read_spool_entry(const fs::path& entry, std::string* error) {
  SpoolEntry out;
  try {
    for (const char* name : {"request.json", "result.json", "cloud.ply"}) {
      if (!fs::is_regular_file(entry / name))
        throw std::runtime_error(std::string("missing ") + name);
    }
    std::ifstream req_in(entry / "request.json");
    std::ifstream res_in(entry / "result.json");
    const auto req = nlohmann::json::parse(req_in, nullptr, true);
    const auto res = nlohmann::json::parse(res_in, nullptr, true);
    std::string why;
    if (!from_json(req, out.request, &why) || !from_json(res, out.result, &why)) {
      throw std::runtime_error(why);
    }
    out.cloud = io::read_ply(entry / "cloud.ply");
  } catch (const std::exception& e) {
    *error = entry.string() + ": " + e.what();
    return std::nullopt;
  }
  return out;
}

}  // namespace rangefit::daemon
