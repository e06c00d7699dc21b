// Object model files: a model or an IoError.
#include "io/io_error.hpp"
#include "io/object_model_file.hpp"
#include "test/fuzz/fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)rangefit::io::parse_object_model(rangefit::fuzz::input_text(data, size), "fuzz.toml");
  } catch (const rangefit::io::IoError&) {
  }
  return 0;
}
