// rangefitd's configuration: a config or an error string, never an exception.
#include "daemon/service/config.hpp"
#include "test/fuzz/fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = rangefit::fuzz::input_text(data, size);
  (void)rangefit::daemon::parse_config(text, "fuzz.toml", "/nonexistent");
  return 0;
}
