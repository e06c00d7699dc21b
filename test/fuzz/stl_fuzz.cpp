// STL reader: every input loads or throws IoError; anything else (a crash, a sanitizer report,
// another exception such as bad_alloc) is a finding.
#include "io/io_error.hpp"
#include "io/stl.hpp"
#include "test/fuzz/fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rangefit;
  const auto path = fuzz::input_file(data, size, ".stl");
  try {
    (void)io::read_stl(path);
  } catch (const io::IoError&) {
  }
  return 0;
}
