// [fusion] tables: a config or an error string, never an exception.
#include "fusion/config.hpp"
#include "test/fuzz/fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = rangefit::fuzz::input_text(data, size);
  (void)rangefit::fusion::parse_fusion_config(std::string_view(text), "fuzz.toml");
  return 0;
}
