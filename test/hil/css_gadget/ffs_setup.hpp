#pragma once
// configfs + FunctionFS plumbing for the CSS gadget: the gadget tree (VID:PID, strings, one
// configuration with one FunctionFS function), the descriptor and string blobs written to ep0
// (full-speed 64-byte and high-speed 512-byte bulk IN: dummy_hcd runs at high speed), and UDC
// binding. Every function returns an empty string on success, otherwise what failed.

#include <cstdint>
#include <string>
#include <vector>

namespace rangefit::hil::ffs {

struct GadgetIds {
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::string serial;
  std::string name;  // configfs directory and FunctionFS instance
};

std::string write_text(const std::string& path, const std::string& text);
// Creates /sys/kernel/config/usb_gadget/<name> (removing a stale one first); sets `dir`.
std::string create_gadget(const GadgetIds& ids, std::string& dir);
// Unbinds and removes what create_gadget made. Safe on a partial tree.
void remove_gadget(const std::string& dir);
// The first UDC in /sys/class/udc, or "" when there is none.
std::string first_udc();
// Interface 0 (class 0xFF, iInterface 1) with bulk IN endpoint 1, at full and high speed.
std::vector<std::uint8_t> descriptors();
std::vector<std::uint8_t> strings();

}  // namespace rangefit::hil::ffs
