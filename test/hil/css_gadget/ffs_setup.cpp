#include "test/hil/css_gadget/ffs_setup.hpp"

#include <linux/usb/ch9.h>
#include <linux/usb/functionfs.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace rangefit::hil::ffs {
namespace {

namespace fs = std::filesystem;

std::string hex(std::uint16_t v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%04x", v);
  return buf;
}

template <typename T>
void append(std::vector<std::uint8_t>& out, const T& value) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

std::string make_dir(const std::string& path) {
  if (::mkdir(path.c_str(), 0755) == 0 || errno == EEXIST) return "";
  return "mkdir " + path + ": " + std::strerror(errno);
}

}  // namespace

std::string write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text << std::flush;  // configfs attributes take the value in one write
  return f ? "" : "write " + path + " failed";
}

std::string create_gadget(const GadgetIds& ids, std::string& dir) {
  const std::string root = "/sys/kernel/config/usb_gadget";
  if (!fs::is_directory(root)) return root + " missing (configfs not mounted, libcomposite?)";
  dir = root + "/" + ids.name;
  remove_gadget(dir);
  const std::string f = dir + "/functions/ffs." + ids.name;
  const std::string c = dir + "/configs/c.1";
  for (const std::string& d : {dir, dir + "/strings/0x409", f, c, c + "/strings/0x409"}) {
    if (auto e = make_dir(d); !e.empty()) return e;
  }
  std::string e;
  for (const auto& [file, value] :
       {std::pair<std::string, std::string>{"idVendor", hex(ids.vendor_id)},
        {"idProduct", hex(ids.product_id)},
        {"bcdUSB", "0x0200"},
        {"bcdDevice", "0x0100"},
        {"strings/0x409/serialnumber", ids.serial},
        {"strings/0x409/manufacturer", "rangefit"},
        {"strings/0x409/product", "Circular Scanning Sensor (simulated)"},
        {"configs/c.1/MaxPower", "100"},
        {"configs/c.1/strings/0x409/configuration", "CSS"}}) {
    if (e = write_text(dir + "/" + file, value); !e.empty()) return e;
  }
  std::error_code ec;
  fs::create_symlink(f, c + "/ffs." + ids.name, ec);
  return ec ? "link function: " + ec.message() : "";
}

void remove_gadget(const std::string& dir) {
  if (dir.empty() || !fs::exists(dir)) return;
  write_text(dir + "/UDC", "\n");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir + "/configs/c.1", ec)) {
    if (entry.is_symlink()) fs::remove(entry.path(), ec);
  }
  // configfs removes attribute files itself; only the directories go, innermost first.
  for (const char* d : {"/configs/c.1/strings/0x409", "/configs/c.1", "/strings/0x409"}) {
    ::rmdir((dir + d).c_str());
  }
  for (const auto& entry : fs::directory_iterator(dir + "/functions", ec)) {
    ::rmdir(entry.path().c_str());
  }
  ::rmdir(dir.c_str());
}

std::string first_udc() {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/sys/class/udc", ec)) {
    return entry.path().filename();
  }
  return "";
}

std::vector<std::uint8_t> descriptors() {
  struct __attribute__((packed)) Speed {
    usb_interface_descriptor interface;
    usb_endpoint_descriptor_no_audio in;
  };
  auto speed = [](std::uint16_t max_packet) {
    Speed s{};
    s.interface = {sizeof(usb_interface_descriptor),
                   USB_DT_INTERFACE,
                   0,
                   0,
                   1,
                   USB_CLASS_VENDOR_SPEC,
                   0,
                   0,
                   1};
    s.in = {USB_DT_ENDPOINT_SIZE,   USB_DT_ENDPOINT,     1 | USB_DIR_IN,
            USB_ENDPOINT_XFER_BULK, htole16(max_packet), 0};
    return s;
  };
  usb_functionfs_descs_head_v2 head{};
  head.magic = htole32(FUNCTIONFS_DESCRIPTORS_MAGIC_V2);
  head.flags = htole32(FUNCTIONFS_HAS_FS_DESC | FUNCTIONFS_HAS_HS_DESC);
  const std::uint32_t count = htole32(2);  // descriptors per speed
  head.length = htole32(sizeof head + 2 * sizeof count + 2 * sizeof(Speed));
  std::vector<std::uint8_t> out;
  append(out, head);
  append(out, count);
  append(out, count);
  append(out, speed(64));   // full speed
  append(out, speed(512));  // high speed
  return out;
}

std::vector<std::uint8_t> strings() {
  const char text[] = "CSS bulk";
  usb_functionfs_strings_head head{};
  head.magic = htole32(FUNCTIONFS_STRINGS_MAGIC);
  head.length = htole32(static_cast<std::uint32_t>(sizeof head + 2 + sizeof text));
  head.str_count = htole32(1);
  head.lang_count = htole32(1);
  std::vector<std::uint8_t> out;
  append(out, head);
  append(out, htole16(std::uint16_t{0x0409}));
  for (const char ch : text) append(out, ch);
  return out;
}

}  // namespace rangefit::hil::ffs
