#include "daemon/rangefitd/systemd_notify.hpp"

#include <systemd/sd-daemon.h>

#include <string>

namespace rangefit::daemon {

void SdNotifier::notify(std::string_view state) {
  const std::string s(state);
  sd_notify(0, s.c_str());
}

hal::Duration watchdog_interval() {
  std::uint64_t usec = 0;
  if (sd_watchdog_enabled(0, &usec) <= 0) return hal::Duration::zero();
  return std::chrono::microseconds(usec);
}

bool WatchdogFeeder::tick(hal::Timestamp now, hal::Timestamp last_progress, std::string* why) {
  if (now - last_progress <= stall_limit_) {
    stalled_ = false;
    notifier_.notify("WATCHDOG=1");
    return true;
  }
  if (!stalled_ && why != nullptr) {
    const double s = std::chrono::duration<double>(now - last_progress).count();
    *why = "pipeline made no progress for " + std::to_string(s) + " s; watchdog not fed";
  }
  stalled_ = true;
  return false;
}

}  // namespace rangefit::daemon
