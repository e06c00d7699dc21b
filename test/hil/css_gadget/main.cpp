// css_gadget: the simulated Circular Scanning Sensor as a USB device (FunctionFS on a UDC), for
// running the daemon or the CLI unchanged against it in the HIL VM. Needs root, configfs mounted
// and dummy_hcd/libcomposite/usb_f_fs loaded (test/hil/run_vm.sh does both).
//   css_gadget [--scene PATH] [--vid 0x1d6b] [--pid 0x0105] [--serial S] [--offset-us US]
//              [--drift-ppm PPM] [--counter-bits N] [--wrap-after-s S] [--udc NAME]
//   css_gadget --scene PATH --record FILE.frames   (casts the scan and saves it; no USB, no root)
// PATH is a scene (.toml) or a recorded scan (.frames); without it, a synthetic pattern.
// Then one command per line on stdin: stall, truncate, split, crc, gap (fault on the next
// revolution), unplug, replug, status, quit (or end of input).
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "test/hil/css_gadget/css_gadget.hpp"

namespace {

int usage(const char* why) {
  std::fprintf(stderr, "css_gadget: %s\n(see the header of test/hil/css_gadget/main.cpp)\n", why);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rangefit::hil;
  CssGadgetOptions o;
  double wrap_after_s = -1.0;
  std::string record;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return usage(("missing value after " + arg).c_str());
    const char* v = argv[++i];
    char* end = nullptr;
    const double number = std::strtod(v, &end);
    const bool numeric = end != v && *end == '\0';
    if (arg == "--scene")
      o.scene_path = v;
    else if (arg == "--serial")
      o.serial = v;
    else if (arg == "--udc")
      o.udc = v;
    else if (arg == "--record")
      record = v;
    else if (!numeric)
      return usage(("not a number: " + std::string(v)).c_str());
    else if (arg == "--vid")
      o.vendor_id = static_cast<std::uint16_t>(std::strtoul(v, nullptr, 0));
    else if (arg == "--pid")
      o.product_id = static_cast<std::uint16_t>(std::strtoul(v, nullptr, 0));
    else if (arg == "--offset-us")
      o.clock.offset_us = number;
    else if (arg == "--drift-ppm")
      o.clock.drift_ppm = number;
    else if (arg == "--counter-bits" && number >= 16 && number <= 64)
      o.clock.counter_bits = static_cast<int>(number);
    else if (arg == "--wrap-after-s" && number >= 0)
      wrap_after_s = number;
    else
      return usage(("unknown option or bad value: " + arg).c_str());
  }
  if (wrap_after_s >= 0) {
    o.clock.offset_us =
        DeviceClockModel::offset_wrapping_after(rangefit::hal::monotonic_now(),
                                                std::chrono::duration_cast<rangefit::hal::Duration>(
                                                    std::chrono::duration<double>(wrap_after_s)),
                                                o.clock.drift_ppm, o.clock.counter_bits);
  }
  if (!record.empty()) {
    const RevolutionSource source(o.scene_path);
    if (!source.error().empty()) return usage(source.error().c_str());
    return source.save(record) ? 0 : usage(("cannot write " + record).c_str());
  }
  CssGadget gadget(o);
  if (!gadget.source().error().empty()) {
    std::fprintf(stderr, "css_gadget: scene: %s (serving the synthetic pattern)\n",
                 gadget.source().error().c_str());
  }
  if (const std::string e = gadget.start(); !e.empty()) {
    std::fprintf(stderr, "css_gadget: %s\n", e.c_str());
    return 1;
  }
  std::printf("css_gadget: bound, %zu revolutions per scan\n", gadget.source().size());
  std::fflush(stdout);
  for (std::string line; std::getline(std::cin, line) && line != "quit";) {
    if (line == "stall")
      gadget.inject(Fault::kStall);
    else if (line == "truncate")
      gadget.inject(Fault::kTruncate);
    else if (line == "split")
      gadget.inject(Fault::kSplit);
    else if (line == "crc")
      gadget.inject(Fault::kBadCrc);
    else if (line == "gap")
      gadget.inject(Fault::kGap);
    else if (line == "unplug")
      gadget.unplug();
    else if (line == "replug")
      gadget.replug();
    else if (line != "status")
      std::fprintf(stderr, "css_gadget: unknown command %s\n", line.c_str());
    std::printf("frames %llu streaming %d rate %u starts %llu\n",
                static_cast<unsigned long long>(gadget.frames_sent()), gadget.streaming() ? 1 : 0,
                static_cast<unsigned>(gadget.rate_centi_hz()),
                static_cast<unsigned long long>(gadget.starts()));
    std::fflush(stdout);
  }
  return 0;
}
