#include "io/cloud_io.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>

#include "io/bounded_reader.hpp"
#include "io/pcd.hpp"
#include "io/ply.hpp"

namespace rangefit::io {
namespace {

CloudFormat format_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".ply") return CloudFormat::kPly;
  if (ext == ".pcd") return CloudFormat::kPcd;
  throw IoError(path, "unknown point-cloud extension '" + path.extension().string() +
                          "' (expected .ply or .pcd)");
}

// An anonymous in-memory file (memfd), reachable by path for the readers and writers, which work
// on paths: standard input or output passes through it. Closed (and gone) with this object.
class MemoryFile {
 public:
  explicit MemoryFile(const char* what) : fd_(memfd_create("rangefit-stdio", MFD_CLOEXEC)) {
    if (fd_ < 0) throw IoError(what, std::string("memfd_create failed: ") + std::strerror(errno));
  }
  ~MemoryFile() { close(fd_); }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;

  std::filesystem::path path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_;
};

// Re-throws an IoError about `inner` (the memory file) as one about `outer` ("stdin"/"stdout").
[[noreturn]] void rethrow_as(const IoError& e, const std::filesystem::path& inner,
                             const char* outer) {
  std::string problem = e.what();
  const std::string prefix = inner.string() + ": ";
  if (problem.starts_with(prefix)) problem.erase(0, prefix.size());
  throw IoError(outer, problem);
}

// Reads file descriptor 0 to its end, unbuffered (nothing else of the process reads stdin).
std::string read_all_stdin() {
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = read(STDIN_FILENO, buffer, sizeof(buffer));
    if (n == 0) return bytes;
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw IoError("stdin", std::string("read failed: ") + std::strerror(errno));
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
}

PointCloud read_stdin(CloudReadReport* report) {
  std::string bytes = read_all_stdin();
  if (bytes.empty()) throw IoError("stdin", "empty, no PLY or PCD data (nothing piped in?)");
  MemoryFile file("stdin");
  try {
    detail::save_file(file.path(), bytes);
    // A PLY file starts with the line "ply"; anything else goes to the PCD reader, which names
    // what is wrong with it.
    const bool ply = bytes.starts_with("ply\n") || bytes.starts_with("ply\r\n");
    bytes = {};
    return ply ? read_ply(file.path(), report) : read_pcd(file.path(), report);
  } catch (const IoError& e) {
    rethrow_as(e, file.path(), "stdin");
  }
}

void write_file(const std::filesystem::path& path, const PointCloud& cloud, CloudFormat format,
                Precision precision) {
  if (format == CloudFormat::kPly) {
    write_ply(path, cloud, PlyEncoding::kBinaryLittleEndian, precision);
  } else {
    write_pcd(path, cloud, PcdEncoding::kBinary, precision);
  }
}

void write_stdout(const PointCloud& cloud, Precision precision, CloudFormat format) {
  MemoryFile file("stdout");
  std::string bytes;
  try {
    write_file(file.path(), cloud, format, precision);
    bytes = detail::load_file(file.path());
  } catch (const IoError& e) {
    rethrow_as(e, file.path(), "stdout");
  }
  std::cout.flush();  // text printed before the cloud stays before it
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = write(STDOUT_FILENO, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw IoError("stdout", std::string("write failed: ") + std::strerror(errno));
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace

PointCloud read_cloud(const std::filesystem::path& path, CloudReadReport* report) {
  if (is_stdio(path)) return read_stdin(report);
  return format_of(path) == CloudFormat::kPly ? read_ply(path, report) : read_pcd(path, report);
}

void write_cloud(const std::filesystem::path& path, const PointCloud& cloud, Precision precision,
                 std::optional<CloudFormat> format) {
  if (is_stdio(path)) return write_stdout(cloud, precision, format.value_or(CloudFormat::kPly));
  write_file(path, cloud, format ? *format : format_of(path), precision);
}

}  // namespace rangefit::io
