// FHPP telegrams from Modbus registers as a drive (or anything on port 502) answers: any number
// of registers in either byte order decodes or is refused, and what decodes encodes back to the
// same registers' meaning.
#include <cstdlib>
#include <vector>

#include "drivers/modbus/fhpp_codec.hpp"
#include "test/fuzz/fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rangefit::drivers::fhpp;
  rangefit::fuzz::ByteReader in(data, size);
  std::vector<std::uint16_t> regs;
  while (!in.empty() && regs.size() < 64) regs.push_back(in.take<std::uint16_t>());
  for (const auto order : {ByteOrder::kLowByteFirst, ByteOrder::kHighByteFirst}) {
    if (const auto input = decode_input(regs, order)) {
      const auto again = decode_input(encode(*input, order), order);
      if (!again || !(*again == *input)) std::abort();
    }
    if (const auto output = decode_output(regs, order)) {
      const auto again = decode_output(encode(*output, order), order);
      if (!again || !(*again == *output)) std::abort();
    }
  }
  return 0;
}
