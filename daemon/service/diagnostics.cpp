#include "daemon/service/diagnostics.hpp"

#include <fmt/format.h>

namespace rangefit::daemon {
namespace {

std::uint8_t level_of(hal::DeviceState s) {
  switch (s) {
    case hal::DeviceState::kReady:
    case hal::DeviceState::kStreaming:
      return kDiagOk;
    case hal::DeviceState::kConnecting:
      return kDiagWarn;
    case hal::DeviceState::kDisconnected:
    case hal::DeviceState::kFault:
      return kDiagError;
  }
  return kDiagError;
}

}  // namespace

std::vector<DiagStatus> DiagnosticsBuilder::build(const std::vector<NamedHealth>& devices,
                                                  const PipelineSnapshot& pipeline,
                                                  hal::Timestamp now) {
  std::vector<DiagStatus> out;
  for (const auto& [name, h] : devices) {
    DiagStatus s;
    s.level = level_of(h.state);
    s.name = "rangefitd: device " + name;
    s.hardware_id = h.hardware_id.empty() ? name : h.hardware_id;
    s.message = h.message.empty() ? hal::to_string(h.state) : h.message;
    double rate = 0.0;
    if (auto it = last_samples_.find(name); it != last_samples_.end() && now > it->second.first) {
      rate = static_cast<double>(h.counters.samples - it->second.second) /
             std::chrono::duration<double>(now - it->second.first).count();
    }
    last_samples_[name] = {now, h.counters.samples};
    const auto& c = h.counters;
    s.values = {{"state", hal::to_string(h.state)},
                {"rate_hz", fmt::format("{:.1f}", rate)},
                {"samples", std::to_string(c.samples)},
                {"dropped", std::to_string(c.dropped)},
                {"gaps", std::to_string(c.gaps)},
                {"crc_errors", std::to_string(c.crc_errors)},
                {"timeouts", std::to_string(c.timeouts)},
                {"faults", std::to_string(c.faults)},
                {"reconnects", std::to_string(c.reconnects)},
                {"last_error", h.message}};
    out.push_back(std::move(s));
  }
  DiagStatus p;
  p.name = "rangefitd: pipeline";
  p.hardware_id = "rangefitd";
  p.level = pipeline.stalled                                         ? kDiagError
            : pipeline.state == LifecycleState::kFault               ? kDiagError
            : pipeline.rejected_busy > 0 && pipeline.queue_depth > 0 ? kDiagWarn
                                                                     : kDiagOk;
  p.message = pipeline.stalled ? "stalled" : to_string(pipeline.state);
  if (pipeline.state == LifecycleState::kFault) p.message += ": " + pipeline.last_error;
  p.values = {{"state", to_string(pipeline.state)},
              {"queue_depth", std::to_string(pipeline.queue_depth)},
              {"completed", std::to_string(pipeline.completed)},
              {"rejected_busy", std::to_string(pipeline.rejected_busy)},
              {"last_error", pipeline.last_error}};
  out.push_back(std::move(p));
  return out;
}

}  // namespace rangefit::daemon
