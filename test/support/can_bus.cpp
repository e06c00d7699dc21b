#include "test/support/can_bus.hpp"

#include <algorithm>
#include <array>

namespace rangefit::sim {

using drivers::can::CanFrame;

SimCanBus::SimCanBus(std::unique_ptr<drivers::can::CanTransport> transport)
    : transport_(std::move(transport)) {}

SimCanBus::~SimCanBus() { stop(); }

void SimCanBus::add(std::shared_ptr<SimCanDevice> device) {
  devices_.push_back(std::move(device));
  next_.push_back(hal::Timestamp{0});
}

void SimCanBus::start() {
  if (thread_.joinable()) return;
  stop_ = false;
  thread_ = std::thread([this] { run(); });
}

void SimCanBus::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void SimCanBus::run() {
  std::array<CanFrame, 64> frames{};
  while (!stop_.load(std::memory_order_relaxed)) {
    hal::Timestamp now = hal::monotonic_now();
    hal::Timestamp wake = now + std::chrono::milliseconds(20);
    for (std::size_t i = 0; i < devices_.size(); ++i) {
      if (now >= next_[i]) next_[i] = devices_[i]->tick(now, *transport_);
      wake = std::min(wake, next_[i]);
    }
    now = hal::monotonic_now();
    const auto r =
        transport_->receive(frames, std::max<hal::Duration>(wake - now, hal::Duration{0}));
    if (r.link_down) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      (void)transport_->reopen();
      continue;
    }
    for (std::size_t k = 0; k < r.frames; ++k) {
      for (auto& d : devices_) d->on_frame(frames[k], *transport_);
    }
  }
}

}  // namespace rangefit::sim
