#pragma once
// Simulated CAN devices on one transport: a thread that hands every received frame to each
// device and lets each device run its periodic work (heartbeats, free-running profiles). The
// devices speak the real wire protocols through the drivers' codecs, so the same driver code runs
// against them over the in-process transport (unit tests) or a vcan interface (HIL VM).

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "drivers/can/transport.hpp"

namespace rangefit::sim {

class SimCanDevice {
 public:
  virtual ~SimCanDevice() = default;
  // Called on the bus thread for every frame on the bus (including other devices' frames).
  virtual void on_frame(const drivers::can::CanFrame& frame, drivers::can::CanTransport& bus) = 0;
  // Periodic work; returns when it wants to be called again.
  virtual hal::Timestamp tick(hal::Timestamp now, drivers::can::CanTransport& bus) = 0;
};

class SimCanBus {
 public:
  explicit SimCanBus(std::unique_ptr<drivers::can::CanTransport> transport);
  ~SimCanBus();
  SimCanBus(const SimCanBus&) = delete;
  SimCanBus& operator=(const SimCanBus&) = delete;

  // Devices are added before start().
  void add(std::shared_ptr<SimCanDevice> device);
  void start();
  void stop();
  drivers::can::CanTransport& transport() { return *transport_; }

 private:
  void run();

  std::unique_ptr<drivers::can::CanTransport> transport_;
  std::vector<std::shared_ptr<SimCanDevice>> devices_;
  std::vector<hal::Timestamp> next_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
};

}  // namespace rangefit::sim
