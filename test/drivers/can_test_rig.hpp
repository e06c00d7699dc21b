#pragma once
// Shared by the CAN driver tests (in-process transport) and the HIL tests (vcan): waiting for a
// condition, draining a source, and a driver wired to simulated devices on the other end of an
// in-process bus.

#include <chrono>
#include <initializer_list>
#include <memory>
#include <thread>
#include <vector>

#include "hal/source.hpp"
#include "test/support/can_bus.hpp"
#include "test/support/inprocess_transport.hpp"

namespace rangefit::drivers::can::test {

using namespace std::chrono_literals;

// Polls pred every 2 ms until it holds (true) or the limit passes (false).
template <class Pred>
bool eventually(Pred pred, std::chrono::milliseconds limit = 3000ms) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!pred()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(2ms);
  }
  return true;
}

// Reads from source until it has delivered at least n samples or the limit passes.
template <class Sample>
std::vector<Sample> collect(hal::SampleSource<Sample>& source, std::size_t n,
                            std::chrono::milliseconds limit = 3000ms) {
  std::vector<Sample> out;
  eventually(
      [&] {
        source.read(out, 10ms);
        return out.size() >= n;
      },
      limit);
  return out;
}

// A driver on one end of an in-process bus and simulated devices on the other. Nothing runs
// until the test starts the bus and the driver (in the order the test needs).
template <class Driver>
struct InProcessRig {
  InProcessTransport* link = nullptr;      // the driver's end: filters, link down
  InProcessTransport* sim_link = nullptr;  // the devices' end: hand-made frames
  std::unique_ptr<sim::SimCanBus> bus;
  std::unique_ptr<Driver> driver;

  template <class Config>
  void wire(const Config& config, const FrameFilter& filter,
            std::initializer_list<std::shared_ptr<sim::SimCanDevice>> devices) {
    auto [a, b] = InProcessTransport::make_pair(filter);
    link = a.get();
    sim_link = b.get();
    bus = std::make_unique<sim::SimCanBus>(std::move(b));
    for (const auto& d : devices) bus->add(d);
    driver = std::make_unique<Driver>(config, std::move(a));
  }
  void stop() {
    if (driver) driver->stop();
    if (bus) bus->stop();
  }
  ~InProcessRig() { stop(); }
};

}  // namespace rangefit::drivers::can::test
