#include "drivers/modbus/modbus_link.hpp"

#include <modbus/modbus.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

#include <cerrno>
#include <string>

namespace rangefit::drivers {
namespace {

using std::chrono::duration_cast;
using std::chrono::microseconds;
using std::chrono::seconds;

void split(hal::Duration d, std::uint32_t& sec, std::uint32_t& usec) {
  const auto us = duration_cast<microseconds>(d).count();
  sec = static_cast<std::uint32_t>(us / 1000000);
  usec = static_cast<std::uint32_t>(us % 1000000);
  if (sec == 0 && usec == 0) usec = 1;  // libmodbus rejects a zero timeout
}

std::string ms(hal::Duration d) {
  return std::to_string(duration_cast<std::chrono::milliseconds>(d).count()) + " ms";
}

}  // namespace

const char* to_string(LinkError e) {
  switch (e) {
    case LinkError::kNone:
      return "ok";
    case LinkError::kRefused:
      return "connect failed";
    case LinkError::kTimeout:
      return "timeout";
    case LinkError::kConnectionLost:
      return "connection lost";
    case LinkError::kBadReply:
      return "bad reply";
    case LinkError::kException:
      return "exception reply";
  }
  return "unknown";
}

ModbusLink::ModbusLink(ModbusLinkConfig config, const hal::Clock& clock)
    : config_(std::move(config)), clock_(clock) {}

ModbusLink::~ModbusLink() { close(); }

std::string ModbusLink::endpoint() const {
  if (!config_.serial_device.empty()) return config_.serial_device;
  return config_.host + ":" + std::to_string(config_.port);
}

LinkResult ModbusLink::open() {
  close();
  LinkResult r;
  modbus_t* ctx = config_.serial_device.empty()
                      ? modbus_new_tcp(config_.host.c_str(), config_.port)
                      : modbus_new_rtu(config_.serial_device.c_str(), config_.baud, config_.parity,
                                       config_.data_bits, config_.stop_bits);
  if (ctx == nullptr) {
    r.error = LinkError::kRefused;
    r.message = "invalid Modbus endpoint " + endpoint() + ": " + modbus_strerror(errno);
    return r;
  }
  std::uint32_t sec = 0, usec = 0;
  split(config_.response_timeout, sec, usec);
  modbus_set_response_timeout(ctx, sec, usec);
  split(config_.byte_timeout, sec, usec);
  modbus_set_byte_timeout(ctx, sec, usec);
  modbus_set_slave(ctx, config_.unit_id);
  if (modbus_connect(ctx) == -1) {
    const int err = errno;
    modbus_free(ctx);
    r.error = LinkError::kRefused;
    r.message = "cannot connect to " + endpoint() + ": " + modbus_strerror(err);
    return r;
  }
  if (config_.serial_device.empty()) {
    const int s = modbus_get_socket(ctx);
    const int on = 1;
    const int idle = static_cast<int>(duration_cast<seconds>(config_.keepalive_idle).count());
    const int intvl = static_cast<int>(duration_cast<seconds>(config_.keepalive_interval).count());
    setsockopt(s, SOL_SOCKET, SO_KEEPALIVE, &on, sizeof on);
    setsockopt(s, IPPROTO_TCP, TCP_KEEPIDLE, &idle, sizeof idle);
    setsockopt(s, IPPROTO_TCP, TCP_KEEPINTVL, &intvl, sizeof intvl);
    setsockopt(s, IPPROTO_TCP, TCP_KEEPCNT, &config_.keepalive_count,
               sizeof config_.keepalive_count);
    setsockopt(s, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);  // one small telegram per cycle
  }
  ctx_ = ctx;
  return r;
}

void ModbusLink::close() {
  if (ctx_ == nullptr) return;
  modbus_close(ctx_);
  modbus_free(ctx_);
  ctx_ = nullptr;
}

LinkResult ModbusLink::classify(int err, LinkResult r) const {
  if (err == ETIMEDOUT) {
    r.error = LinkError::kTimeout;
    r.message = "no reply from " + endpoint() + " within the response timeout (" +
                ms(config_.response_timeout) + ")";
  } else if (err > MODBUS_ENOBASE && err <= EMBXGTAR) {
    r.error = LinkError::kException;
    r.exception_code = err - MODBUS_ENOBASE;
    r.message = "exception " + std::to_string(r.exception_code) + " (" + modbus_strerror(err) +
                ") from unit " + std::to_string(config_.unit_id) + " at " + endpoint();
  } else if (err >= EMBBADCRC && err <= EMBBADSLAVE) {
    r.error = LinkError::kBadReply;
    r.message = std::string("reply does not match the request (") + modbus_strerror(err) +
                "): late, foreign or malformed reply from " + endpoint();
  } else {
    r.error = LinkError::kConnectionLost;
    r.message = "connection to " + endpoint() + " lost mid-request: " + modbus_strerror(err);
  }
  return r;
}

LinkResult ModbusLink::exchange(const fhpp::Registers& out, fhpp::Registers& in) {
  LinkResult r;
  if (ctx_ == nullptr) {
    r.error = LinkError::kConnectionLost;
    r.message = "not connected to " + endpoint();
    return r;
  }
  const int addr = config_.register_address;
  const bool combined = config_.functions == FunctionMode::kReadWrite ||
                        (config_.functions == FunctionMode::kAutoFallback && !fell_back_);
  if (combined) {
    r.request = clock_.now();
    const int rc = modbus_write_and_read_registers(ctx_, addr, fhpp::kTelegramRegisters, out.data(),
                                                   addr, fhpp::kTelegramRegisters, in.data());
    r.reply = clock_.now();
    if (rc == fhpp::kTelegramRegisters) return r;
    const int err = rc == -1 ? errno : EMBMDATA;
    if (err != EMBXILFUN || config_.functions != FunctionMode::kAutoFallback) {
      return classify(err, r);
    }
    fell_back_ = true;  // the device does not know 0x17: use 0x10 + 0x03 from now on
  }
  if (modbus_write_registers(ctx_, addr, fhpp::kTelegramRegisters, out.data()) == -1) {
    return classify(errno, r);
  }
  r.request = clock_.now();
  const int rc = modbus_read_registers(ctx_, addr, fhpp::kTelegramRegisters, in.data());
  r.reply = clock_.now();
  if (rc == fhpp::kTelegramRegisters) return r;
  return classify(rc == -1 ? errno : EMBMDATA, r);
}

}  // namespace rangefit::drivers
