#include "drivers/can/realtime.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <cstring>
#include <string>

namespace rangefit::drivers::can {

hal::Status apply_realtime(const RealtimeConfig& cfg) {
  if (cfg.lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    return hal::Status::Error(std::string("mlockall: ") + std::strerror(errno));
  }
  if (cfg.fifo) {
    sched_param p{};
    p.sched_priority = cfg.priority;
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
    if (err != 0) return hal::Status::Error(std::string("SCHED_FIFO: ") + std::strerror(err));
  }
  return hal::Status::Ok();
}

}  // namespace rangefit::drivers::can
