#include "io/bounded_reader.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <functional>
#include <string>

#include "io/io_error.hpp"
#include "io/ply.hpp"
#include "io/stl.hpp"
#include "test/io/temp_dir.hpp"

namespace rangefit::io {
namespace bounded_reader_test {

std::string reader_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const IoError& e) {
    return e.what();
  }
  return "no IoError";
}

TEST(LoadFile, DevicesAndFifosAreRefusedUnlessAskedForThenCapped) {
  // /dev/zero used to be read until memory ran out; a FIFO without a writer blocked forever.
  test::TempDir dir;
  const auto fifo = dir.path("scan.ply");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(reader_error([&] { read_ply(fifo); }),
            fifo.string() + ": is not a regular file (a device, FIFO or socket)");
  EXPECT_EQ(reader_error([] { read_stl("/dev/zero"); }),
            "/dev/zero: is not a regular file (a device, FIFO or socket)");
  EXPECT_EQ(reader_error([] { detail::load_file("/dev/zero", 100000, /*allow_special=*/true); }),
            "/dev/zero: more than the limit of 100000 bytes");
  EXPECT_EQ(detail::load_file("/dev/null", 10, true), "");
}

TEST(LoadFile, RegularFilesAreCheckedAgainstTheCapBeforeReading) {
  test::TempDir dir;
  const auto file = dir.write("a.stl", std::string(64, 'x'));
  EXPECT_EQ(detail::load_file(file, 64), std::string(64, 'x'));
  EXPECT_EQ(reader_error([&] { detail::load_file(file, 63); }),
            file.string() + ": is 64 bytes, more than the limit of 63");
  EXPECT_EQ(reader_error([&] { read_ply(dir.path("")); }),
            dir.path("").string() + ": is a directory, not a file");
}

}  // namespace bounded_reader_test
}  // namespace rangefit::io
