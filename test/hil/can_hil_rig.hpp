#pragma once
// Shared by the CAN HIL tests: the vcan interface under test, SocketCAN transports on it, the
// simulated devices' bus on their own socket, and shell peers (ip, cansend).

#include <cstdlib>
#include <memory>
#include <string>

#include "drivers/can/socketcan_transport.hpp"
#include "test/drivers/can_test_rig.hpp"
#include "test/support/can_bus.hpp"

namespace rangefit::drivers::can::test {

inline const char* interface() {
  const char* i = std::getenv("RANGEFIT_HIL_CAN");
  return i ? i : "vcan0";
}

inline std::unique_ptr<SocketCanTransport> socket_for(FrameFilter filter, bool fd = false,
                                                      int receive_buffer = 1 << 20) {
  SocketCanConfig c;
  c.interface = interface();
  c.filter = std::move(filter);
  c.fd = fd;
  c.receive_buffer = receive_buffer;
  return std::make_unique<SocketCanTransport>(c);
}

// The simulated devices' end of the bus: their own socket on the same interface.
inline std::unique_ptr<sim::SimCanBus> sim_bus(bool fd) {
  auto t = socket_for({}, fd);
  if (!t->open().ok) return nullptr;
  return std::make_unique<sim::SimCanBus>(std::move(t));
}

inline bool shell(const std::string& command) { return std::system(command.c_str()) == 0; }

// can-utils as an independent peer: one frame in cansend's syntax ("185#3706", "20000040#").
inline bool cansend(const std::string& frame) {
  return shell("cansend " + std::string(interface()) + " " + frame);
}

inline bool set_link(bool up) {
  return shell("ip link set " + std::string(interface()) + (up ? " up" : " down"));
}

}  // namespace rangefit::drivers::can::test
