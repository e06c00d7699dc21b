#include "daemon/dds/models_msg.hpp"

#include "daemon/dds/messages.hpp"

namespace rangefit::daemon {

ModelsOut::ModelsOut(const DaemonConfig& config, std::string frame) : frame_(std::move(frame)) {
  for (const auto& o : config.objects) {
    names_.push_back(o.name);
    counts_.push_back(static_cast<std::uint32_t>(o.model.parts.size()));
    for (const auto& p : o.model.parts) parts_.push_back(p.name);
  }
  for (auto& n : names_) name_ptrs_.push_back(n.data());
  for (auto& p : parts_) part_ptrs_.push_back(p.data());
  const auto n = static_cast<std::uint32_t>(names_.size());
  const auto np = static_cast<std::uint32_t>(parts_.size());
  msg_.header = {wall_time_now(), frame_.data()};
  msg_.names = {n, n, name_ptrs_.data(), false};
  msg_.part_counts = {n, n, counts_.data(), false};
  msg_.part_names = {np, np, part_ptrs_.data(), false};
}

std::vector<ModelInfo> from_msg(const rangefit_msgs_msg_dds__Models_& msg) {
  std::vector<ModelInfo> out;
  std::uint32_t next_part = 0;
  for (std::uint32_t i = 0; i < msg.names._length; ++i) {
    ModelInfo m;
    m.name = msg.names._buffer[i] == nullptr ? "" : msg.names._buffer[i];
    const std::uint32_t count = i < msg.part_counts._length ? msg.part_counts._buffer[i] : 0;
    for (std::uint32_t k = 0; k < count && next_part < msg.part_names._length; ++k, ++next_part) {
      const char* p = msg.part_names._buffer[next_part];
      m.parts.emplace_back(p == nullptr ? "" : p);
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace rangefit::daemon
