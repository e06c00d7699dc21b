#pragma once
// The simulated FHPP drive on Modbus TCP: a libmodbus server on loopback (port 0 = any free port)
// answering 0x17, 0x03 and 0x10 at register 0 with the drive's telegrams, several clients at once.
// Fault hooks for tests: exception replies, 0x17 unsupported, register byte order.

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

#include "drivers/modbus/fhpp_codec.hpp"
#include "hal/device.hpp"
#include "hal/time.hpp"
#include "test/support/modbus_axis_drive.hpp"

namespace rangefit::sim {

struct SimAxisServerConfig {
  std::string host = "127.0.0.1";
  int port = 0;  // 0 = pick a free port; see SimAxisServer::port()
  int unit_id = 1;
  drivers::fhpp::ByteOrder byte_order = drivers::fhpp::ByteOrder::kLowByteFirst;
  bool supports_read_write = true;  // false: 0x17 answered with exception 01 (illegal function)
};

class SimAxisServer {
 public:
  // The drive and the clock must outlive the server; clock nullptr = CLOCK_MONOTONIC.
  SimAxisServer(SimFhppDrive& drive, SimAxisServerConfig config, const hal::Clock* clock = nullptr);
  ~SimAxisServer();
  SimAxisServer(const SimAxisServer&) = delete;
  SimAxisServer& operator=(const SimAxisServer&) = delete;

  hal::Status start();
  void stop();
  int port() const { return port_; }

  // Every request is answered with this Modbus exception code (0 = answer normally).
  void set_exception(int code) { exception_ = code; }
  void set_byte_order(drivers::fhpp::ByteOrder order) { byte_order_ = order; }
  int connections() const { return connections_; }
  std::uint64_t requests() const { return requests_; }

 private:
  void run();
  // Answers one request on client socket fd; false when the connection must be closed.
  bool serve(void* ctx, int fd, int client, const std::uint8_t* req, int len);
  hal::Timestamp now() const;

  SimFhppDrive& drive_;
  SimAxisServerConfig config_;
  const hal::Clock* clock_;
  void* listen_ctx_ = nullptr;  // modbus_t*
  int listen_fd_ = -1;
  int port_ = 0;
  std::atomic<int> exception_{0};
  std::atomic<drivers::fhpp::ByteOrder> byte_order_;
  std::atomic<int> connections_{0};
  std::atomic<std::uint64_t> requests_{0};
  std::atomic<bool> running_{false};
  std::thread thread_;
};

}  // namespace rangefit::sim
