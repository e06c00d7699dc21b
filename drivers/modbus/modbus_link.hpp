#pragma once
// Modbus transport for the FHPP telegram exchange, over libmodbus (TCP, or RTU on a serial line).
// Knows nothing of FHPP bits: it writes 4 registers and reads 4 registers at address 0, and
// classifies what went wrong so the driver can choose between reconnecting and reporting.

#include <chrono>
#include <cstdint>
#include <string>

#include "drivers/modbus/fhpp_codec.hpp"
#include "hal/time.hpp"

typedef struct _modbus modbus_t;  // NOLINT: libmodbus's opaque context

namespace rangefit::drivers {

enum class FunctionMode : std::uint8_t {
  kReadWrite,     // 0x17 read/write multiple registers, one transaction per cycle
  kSeparate,      // 0x10 write then 0x03 read
  kAutoFallback,  // 0x17, switching to 0x10/0x03 once the device answers "illegal function"
};

struct ModbusLinkConfig {
  // TCP when serial_device is empty.
  std::string host = "127.0.0.1";
  int port = 502;
  std::string serial_device;  // e.g. /dev/ttyUSB0 for RTU
  int baud = 115200;
  char parity = 'N';
  int data_bits = 8;
  int stop_bits = 1;
  int unit_id = 1;
  int register_address = 0;  // FHPP telegrams sit at register 0
  FunctionMode functions = FunctionMode::kReadWrite;
  hal::Duration response_timeout = std::chrono::milliseconds(50);
  hal::Duration byte_timeout = std::chrono::milliseconds(20);
  // TCP keepalive, so a half-open connection is found even while no request is in flight.
  hal::Duration keepalive_idle = std::chrono::seconds(1);
  hal::Duration keepalive_interval = std::chrono::seconds(1);
  int keepalive_count = 3;
};

enum class LinkError : std::uint8_t {
  kNone,
  kRefused,         // connect failed (refused, unreachable, timed out)
  kTimeout,         // no (complete) reply within the response/byte timeout
  kConnectionLost,  // reset or closed by the peer mid-request
  kBadReply,        // reply that does not match the request (late, foreign, malformed)
  kException,       // the device answered with a Modbus exception
};
const char* to_string(LinkError e);

struct LinkResult {
  LinkError error = LinkError::kNone;
  int exception_code = 0;    // Modbus exception code when error == kException
  std::string message;       // empty when ok
  hal::Timestamp request{};  // just before the (reading) request left
  hal::Timestamp reply{};    // just after its reply arrived
  bool ok() const { return error == LinkError::kNone; }
};

class ModbusLink {
 public:
  explicit ModbusLink(ModbusLinkConfig config, const hal::Clock& clock);
  ~ModbusLink();
  ModbusLink(const ModbusLink&) = delete;
  ModbusLink& operator=(const ModbusLink&) = delete;

  LinkResult open();
  void close();
  bool is_open() const { return ctx_ != nullptr; }
  // Writes `out` and reads the input telegram into `in`.
  LinkResult exchange(const fhpp::Registers& out, fhpp::Registers& in);
  // True once an "illegal function" answer to 0x17 made an kAutoFallback link use 0x10/0x03.
  bool fell_back() const { return fell_back_; }
  std::string endpoint() const;

 private:
  LinkResult classify(int err, LinkResult r) const;

  ModbusLinkConfig config_;
  const hal::Clock& clock_;
  modbus_t* ctx_ = nullptr;
  bool fell_back_ = false;
};

}  // namespace rangefit::drivers
