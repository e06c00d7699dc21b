#include "daemon/rangefitd/result_board.hpp"

#include <algorithm>

namespace rangefit::daemon {

void ResultBoard::on_cloud(const ScanRequest& request, const PointCloud& cloud) {
  next_.on_cloud(request, cloud);
}

void ResultBoard::on_result(const DetectionResult& result) {
  {
    std::lock_guard lock(mutex_);
    by_id_[result.request_id] = result;
    std::erase(done_order_, result.request_id);
    done_order_.push_back(result.request_id);
    while (done_order_.size() > keep_) {
      by_id_.erase(done_order_.front());
      done_order_.pop_front();
    }
    ++generation_;
  }
  cv_.notify_all();
  next_.on_result(result);
}

void ResultBoard::on_state(LifecycleState state, const std::string& detail,
                           const std::string& active_id, std::size_t queue_depth) {
  {
    std::lock_guard lock(mutex_);
    state_.state = state;
    state_.detail = detail;
    state_.active_id = active_id;
    state_.queue_depth = queue_depth;
  }
  next_.on_state(state, detail, active_id, queue_depth);
}

void ResultBoard::set_diagnostics(std::vector<DiagStatus> statuses) {
  std::lock_guard lock(mutex_);
  state_.diagnostics = std::move(statuses);
}

bool ResultBoard::reserve(const std::string& id) {
  std::lock_guard lock(mutex_);
  const auto it = by_id_.find(id);
  if (it != by_id_.end() && !it->second) return false;
  std::erase(done_order_, id);
  by_id_[id] = std::nullopt;
  return true;
}

std::optional<DetectionResult> ResultBoard::wait_for(const std::string& id,
                                                     std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  std::optional<DetectionResult> out;
  cv_.wait_for(lock, timeout, [&] {
    const auto it = by_id_.find(id);
    if (it != by_id_.end() && it->second) out = it->second;
    return out.has_value() || closed_;
  });
  return out;
}

ResultBoard::Lookup ResultBoard::find(const std::string& id, DetectionResult* out) const {
  std::lock_guard lock(mutex_);
  const auto it = by_id_.find(id);
  if (it == by_id_.end()) return Lookup::kUnknown;
  if (!it->second) return Lookup::kPending;
  *out = *it->second;
  return Lookup::kDone;
}

std::vector<DetectionResult> ResultBoard::latest(std::size_t n) const {
  std::lock_guard lock(mutex_);
  std::vector<DetectionResult> out;
  for (auto it = done_order_.rbegin(); it != done_order_.rend() && out.size() < n; ++it) {
    out.push_back(*by_id_.at(*it));
  }
  return out;
}

BoardState ResultBoard::state() const {
  std::lock_guard lock(mutex_);
  return state_;
}

std::uint64_t ResultBoard::generation() const {
  std::lock_guard lock(mutex_);
  return generation_;
}

bool ResultBoard::closed() const {
  std::lock_guard lock(mutex_);
  return closed_;
}

void ResultBoard::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  cv_.notify_all();
}

}  // namespace rangefit::daemon
