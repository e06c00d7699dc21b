// Motion commands of FhppAxis: each is handed to the commander under the lock, written by the poll
// thread in its next telegram, and waited for until the drive acknowledges it.
#include <spdlog/spdlog.h>

#include "drivers/modbus/fhpp_axis.hpp"

namespace rangefit::drivers {

template <class Request>
hal::Status FhppAxis::command(const char* what, Request request) {
  std::unique_lock lock(mutex_);
  if (!running_) return hal::Status::Error(std::string(what) + " refused: driver not started");
  if (!connected_ || !commander_.last_input()) {
    return hal::Status::Error(std::string(what) + " refused: no connection to the drive (" +
                              (health_.message.empty() ? "connecting" : health_.message) + ")");
  }
  if (config_error_) {
    return hal::Status::Error(std::string(what) + " refused: " + health_.message);
  }
  fhpp::Commander::Ticket ticket;
  hal::Status s = request(commander_, ticket);
  if (!s) {
    spdlog::warn("{}: {}", config_.name, s.message);
    return s;
  }
  const bool done = cv_.wait_for(lock, config_.command_timeout, [&] {
    return commander_.accepted(ticket) || !connected_ || !running_;
  });
  if (done && commander_.accepted(ticket)) return hal::Status::Ok();
  const auto& in = commander_.last_input();
  std::string why =
      std::string(what) + " not acknowledged by the drive within " +
      std::to_string(
          std::chrono::duration_cast<std::chrono::milliseconds>(config_.command_timeout).count()) +
      " ms";
  if (in) why += "; " + fhpp::describe_status(in->scon, in->spos);
  if (!health_.message.empty()) why += "; " + health_.message;
  return hal::Status::Error(why);
}

hal::Status FhppAxis::enable() {
  return command(
      "enable", [](fhpp::Commander& c, fhpp::Commander::Ticket& t) { return c.request_enable(t); });
}

hal::Status FhppAxis::disable() {
  std::lock_guard lock(mutex_);
  commander_.request_disable();
  return hal::Status::Ok();
}

hal::Status FhppAxis::home() {
  return command("home",
                 [](fhpp::Commander& c, fhpp::Commander::Ticket& t) { return c.request_home(t); });
}

hal::Status FhppAxis::move_to(double position_mm, double speed_mm_s) {
  const PositionCheckConfig travel = config_.travel;
  return command("move", [&](fhpp::Commander& c, fhpp::Commander::Ticket& t) {
    return c.request_move(position_mm, speed_mm_s, travel.min_mm, travel.max_mm, t);
  });
}

hal::Status FhppAxis::halt() {
  return command("halt",
                 [](fhpp::Commander& c, fhpp::Commander::Ticket& t) { return c.request_halt(t); });
}

hal::Status FhppAxis::reset_fault() {
  return command("reset",
                 [](fhpp::Commander& c, fhpp::Commander::Ticket& t) { return c.request_reset(t); });
}

bool FhppAxis::motion_complete() const {
  std::lock_guard lock(mutex_);
  return connected_ && commander_.motion_complete();
}

}  // namespace rangefit::drivers
