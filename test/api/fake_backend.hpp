#pragma once
// A Backend standing in for the service: answers detections after a delay, one at a time like
// the cell, busy when its queue is full; remembers results by id.

#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <thread>

#include "api/backend.hpp"

namespace rangefit::api::test {

// The write token the servers under test are started with.
inline const std::string kToken = "t0ken-for-tests";

class FakeBackend : public Backend {
 public:
  std::chrono::milliseconds detect_time{0};
  int capacity = 1000;  // requests in flight before busy
  std::atomic<int> detections{0};
  std::filesystem::path cloud_file;  // served for every finished id
  std::filesystem::path model_file;  // model.toml of every finished id, when set
  std::vector<std::string> asked_files;  // names result_file() was asked for
  std::atomic<bool> hold{false};     // detections do not finish while set (a long scan)

  Answer detect(const nlohmann::json& request, bool wait) override {
    if (!request.contains("kind")) return error_answer(Status::kBadRequest, "request: no kind");
    if (in_flight_.fetch_add(1) >= capacity) {
      --in_flight_;
      return error_answer(Status::kBusy, "busy: the cell is scanning");
    }
    std::string id = request.value("id", std::string());
    if (id.empty()) id = std::string("r").append(std::to_string(next_id_++));
    if (!wait) {
      {
        std::lock_guard lock(mutex_);
        results_[id] = std::nullopt;
      }
      std::thread([this, id] { finish(id); }).detach();
      return {Status::kAccepted, {{"id", id}}};
    }
    return {Status::kOk, finish(id)};
  }

  Answer result(const std::string& id) override {
    std::lock_guard lock(mutex_);
    const auto it = results_.find(id);
    if (it == results_.end()) return error_answer(Status::kNotFound, "no result " + id);
    if (!it->second) return {Status::kAccepted, {{"id", id}}};
    return {Status::kOk, *it->second};
  }

  Answer recent(std::size_t n) override {
    std::lock_guard lock(mutex_);
    nlohmann::json list = nlohmann::json::array();
    for (auto it = results_.rbegin(); it != results_.rend() && list.size() < n; ++it) {
      if (it->second) list.push_back(*it->second);
    }
    return {Status::kOk, {{"results", list}}};
  }

  Answer state() override {
    return {Status::kOk, {{"state", "ready"}, {"in_flight", in_flight_.load()}}};
  }

  std::optional<std::filesystem::path> result_file(const std::string& id,
                                                   const std::string& name) override {
    std::lock_guard lock(mutex_);
    const auto it = results_.find(id);
    if (it == results_.end() || !it->second) return std::nullopt;
    asked_files.push_back(name);
    if (name == "cloud.ply") return cloud_file;
    if (name == "model.toml" && !model_file.empty()) return model_file;
    return std::nullopt;
  }

  ~FakeBackend() override {
    // Detached async detections finish before the members go.
    while (in_flight_ > 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }

 private:
  nlohmann::json finish(const std::string& id) {
    std::this_thread::sleep_for(detect_time);
    while (hold) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const nlohmann::json r = {{"request_id", id}, {"found", true}, {"bore_radius_mm", 5.0}};
    {
      std::lock_guard lock(mutex_);
      results_[id] = r;
    }
    ++detections;
    --in_flight_;
    return r;
  }

  std::atomic<int> in_flight_{0};
  std::atomic<int> next_id_{1};
  std::mutex mutex_;
  std::map<std::string, std::optional<nlohmann::json>> results_;
};

}  // namespace rangefit::api::test
