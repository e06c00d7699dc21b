// The guarded TOML parse every loader uses (io/toml_file.hpp): parses or throws TomlError, never
// overflows the stack or reaches undefined behaviour inside toml++.
#include "io/toml_file.hpp"
#include "test/fuzz/fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)rangefit::io::parse_toml(rangefit::fuzz::input_text(data, size), "fuzz.toml");
  } catch (const rangefit::io::TomlError&) {
  }
  return 0;
}
