#pragma once
// REP 107 diagnostics for rt/diagnostics: one status per device (state, sample rate, drop and
// error counters, last problem) and one for the pipeline (state, queue depth, last error).
// Rates are computed from the counter deltas between two calls.

#include <map>
#include <string>
#include <vector>

#include "daemon/service/lifecycle.hpp"
#include "daemon/service/pipeline.hpp"

namespace rangefit::daemon {

struct PipelineSnapshot {
  LifecycleState state = LifecycleState::kIdle;
  std::size_t queue_depth = 0;
  std::uint64_t completed = 0;
  std::uint64_t rejected_busy = 0;
  std::string last_error;
  bool stalled = false;
};

class DiagnosticsBuilder {
 public:
  std::vector<DiagStatus> build(const std::vector<NamedHealth>& devices,
                                const PipelineSnapshot& pipeline, hal::Timestamp now);

 private:
  std::map<std::string, std::pair<hal::Timestamp, std::uint64_t>> last_samples_;
};

}  // namespace rangefit::daemon
