#pragma once
// sd_notify(3) for Type=notify services, and the watchdog rule: WATCHDOG=1 is sent only while
// the pipeline makes progress, so systemd restarts a daemon whose worker hangs (e.g. a driver
// call that never returns), not just one that crashed.

#include <string>
#include <string_view>

#include "hal/time.hpp"

namespace rangefit::daemon {

class Notifier {
 public:
  virtual ~Notifier() = default;
  virtual void notify(std::string_view state) = 0;  // "READY=1", "STATUS=...", ...
};

// Sends to $NOTIFY_SOCKET; does nothing when run by hand (no socket).
class SdNotifier final : public Notifier {
 public:
  void notify(std::string_view state) override;
};

// Watchdog interval systemd asked for (WatchdogSec=), or 0 when the watchdog is off.
hal::Duration watchdog_interval();

// Decides, on each tick of the main loop, whether to feed the watchdog.
class WatchdogFeeder {
 public:
  WatchdogFeeder(Notifier& notifier, hal::Duration stall_limit)
      : notifier_(notifier), stall_limit_(stall_limit) {}
  void set_stall_limit(hal::Duration d) { stall_limit_ = d; }

  // Feeds when the last progress is within the stall limit of now. Returns whether it fed;
  // the first missed feed after healthy ones sets *why (to be logged), later ones do not.
  bool tick(hal::Timestamp now, hal::Timestamp last_progress, std::string* why);

 private:
  Notifier& notifier_;
  hal::Duration stall_limit_;
  bool stalled_ = false;
};

}  // namespace rangefit::daemon
