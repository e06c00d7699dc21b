#include "drivers/usb/revolution_translator.hpp"

namespace rangefit::drivers::css_usb {

void RevolutionTranslator::translate(const WireRevolution& r, hal::Timestamp completed) {
  out_.sequence = r.sequence;
  out_.flags = r.flags;
  out_.period = clock_.duration_to_host(r.period_us);
  if (const auto stamp = clock_.to_host(r.device_time_us)) {
    out_.stamp = *stamp;
  } else {
    // The transfer completes after the revolution's last sample; the index pulse (sample 0)
    // was one period earlier, plus the bus and scheduling latency.
    out_.stamp = completed - out_.period - completion_latency_;
    ++host_stamped_;
  }
  for (std::size_t i = 0; i < kSamples; ++i) {
    out_.range_mm[i] = range_mm(r.samples[i].range_um);
    out_.intensity[i] = r.samples[i].intensity;
    out_.quality[i] = r.samples[i].quality;
  }
}

}  // namespace rangefit::drivers::css_usb
