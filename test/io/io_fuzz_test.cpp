// Fuzz-style robustness: seeded random truncations, byte flips and hostile numbers over valid
// files of every format and encoding. Each variant must either load or throw IoError; anything
// else (a crash, another exception, an allocation out of proportion to the file) fails the test.

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "io/cloud_io.hpp"
#include "io/pcd.hpp"
#include "io/ply.hpp"
#include "io/stl.hpp"
#include "test/io/cloud_fixtures.hpp"
#include "test/io/temp_dir.hpp"
#include "test/support/allocation_watch/allocation_watch.hpp"

namespace rangefit::io {
namespace io_fuzz_test {

using test::TempDir;

struct Sample {
  std::string name;  // extension selects the reader
  std::string bytes;
};

std::vector<Sample> valid_files(const TempDir& dir) {
  PointCloud cloud = test::organised_cloud();
  std::vector<Sample> samples;
  auto add = [&](const std::string& name, auto write) {
    const auto file = dir.path(name);
    write(file);
    samples.push_back({name, TempDir::read(file)});
  };
  add("ascii.ply", [&](const auto& f) { write_ply(f, cloud, PlyEncoding::kAscii); });
  add("le.ply", [&](const auto& f) { write_ply(f, cloud, PlyEncoding::kBinaryLittleEndian); });
  add("be.ply", [&](const auto& f) { write_ply(f, cloud, PlyEncoding::kBinaryBigEndian); });
  add("ascii.pcd", [&](const auto& f) { write_pcd(f, cloud, PcdEncoding::kAscii); });
  add("binary.pcd", [&](const auto& f) { write_pcd(f, cloud, PcdEncoding::kBinary); });
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  add("binary.stl", [&](const auto& f) { write_stl(f, mesh); });
  samples.push_back({"ascii.stl",
                     "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                     "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n"});
  // A PLY with a face element (list property) and a binary_compressed PCD, as other tools write.
  std::string faces =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 9; ++i) test::append_le(faces, static_cast<float>(i));
  faces += '\x03';
  for (int i = 0; i < 3; ++i) test::append_le(faces, i);
  samples.push_back({"faces.ply", faces});
  std::string raw;
  for (int i = 0; i < 12; ++i) test::append_le(raw, static_cast<float>(i));
  std::string compressed =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 2\nPOINTS 4\n"
      "DATA binary_compressed\n";
  test::append_le(compressed, static_cast<std::uint32_t>(raw.size() + 2));
  test::append_le(compressed, static_cast<std::uint32_t>(raw.size()));
  compressed += static_cast<char>(31);
  compressed += raw.substr(0, 32);
  compressed += static_cast<char>(15);
  compressed += raw.substr(32);
  samples.push_back({"compressed.pcd", compressed});
  return samples;
}

std::string mutate(std::string bytes, std::mt19937& rng) {
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n)(rng); };
  switch (pick(4)) {
    case 0:  // truncation
      bytes.resize(pick(bytes.size()));
      break;
    case 1:  // a few random bytes
      for (std::size_t k = 0, n = 1 + pick(3); k < n && !bytes.empty(); ++k) {
        bytes[pick(bytes.size() - 1)] = static_cast<char>(pick(255));
      }
      break;
    case 2: {  // a digit turned into a huge or negative number (header counts, sizes)
      std::vector<std::size_t> digits;
      for (std::size_t i = 0; i < bytes.size() && i < 600; ++i) {
        if (bytes[i] >= '0' && bytes[i] <= '9') digits.push_back(i);
      }
      if (digits.empty()) break;
      const char* numbers[] = {"4000000000", "-1", "99999999999999999999", "2147483647", "0"};
      bytes.replace(digits[pick(digits.size() - 1)], 1, numbers[pick(4)]);
      break;
    }
    case 3: {  // a 32-bit field set to an extreme (binary counts, lengths)
      if (bytes.size() < 4) break;
      const std::uint32_t values[] = {0xffffffffu, 0x7fffffffu, 0x80000000u, 0x10000u};
      const std::uint32_t v = values[pick(3)];
      std::memcpy(bytes.data() + pick(bytes.size() - 4), &v, 4);
      break;
    }
    default: {  // a line of junk inserted (unknown keywords, megabyte lines)
      const std::string junk = pick(1) ? std::string(pick(1) ? 70000 : 10, 'x') + "\n" : "\n";
      bytes.insert(pick(bytes.size()), junk);
      break;
    }
  }
  return bytes;
}

TEST(IoFuzz, MutatedFilesOnlyLoadOrThrowIoError) {
  TempDir dir;
  const std::vector<Sample> samples = valid_files(dir);
  std::mt19937 rng(20261123);
  constexpr int kVariantsPerFile = 400;
  int loaded = 0;
  int rejected = 0;
  for (const Sample& sample : samples) {
    const auto file = dir.path("mutant_" + sample.name);
    for (int v = 0; v < kVariantsPerFile; ++v) {
      const std::string bytes = mutate(sample.bytes, rng);
      // Unlink first: rewriting a truncated file makes ext4 flush it to disk every time.
      std::filesystem::remove(file);
      TempDir::write_to(file, bytes);
      // The largest single allocation while reading: proves hostile counts are checked against
      // the file size before anything is reserved.
      rangefit::test::start_watching_allocations();
      try {
        if (file.extension() == ".stl") {
          read_stl(file);
        } else {
          read_cloud(file);
        }
        ++loaded;
      } catch (const IoError& e) {
        ++rejected;
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
      } catch (const std::exception& e) {
        ADD_FAILURE() << sample.name << " variant " << v << ": " << e.what();
      }
      const rangefit::test::AllocationStats heap = rangefit::test::stop_watching_allocations();
      // Whole file (once, plus copies in flight), points as doubles and grids: a bounded multiple.
      EXPECT_LE(heap.largest, 64 * bytes.size() + (8u << 20))
          << sample.name << " variant " << v;
    }
  }
  // Both outcomes occur, so the mutations neither all miss nor all break the files.
  EXPECT_GT(loaded, 100);
  EXPECT_GT(rejected, 1000);
}

TEST(IoFuzz, ValidFilesLoad) {
  TempDir dir;
  for (const Sample& sample : valid_files(dir)) {
    const auto file = dir.write("copy_" + sample.name, sample.bytes);
    if (file.extension() == ".stl") {
      EXPECT_FALSE(read_stl(file).triangles.empty()) << sample.name;
    } else {
      EXPECT_FALSE(read_cloud(file).empty()) << sample.name;
    }
  }
}

}  // namespace io_fuzz_test
}  // namespace rangefit::io
