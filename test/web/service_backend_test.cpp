// The pieces between the interfaces and the service: the [http]/[tcp] configuration, requests
// decoded from JSON, results told apart as the interfaces answer them, and the result board.
#include <gtest/gtest.h>

#include <future>
#include <thread>

#include "daemon/service/config.hpp"
#include "daemon/rangefitd/http_backend.hpp"
#include "daemon/rangefitd/result_board.hpp"
#include "detect/bore/bore_result.hpp"

namespace rangefit::daemon {
namespace service_backend_test {

std::string config_error(const std::string& toml) { return parse_config(toml, "t.toml").error; }

TEST(InterfaceConfig, ListenAndTokenAreCheckedAndNamed) {
  const auto ok = parse_config(
      "[http]\nlisten = \"127.0.0.1:8080\"\ntoken = \"long-enough\"\n[tcp]\nlisten = "
      "\"localhost:8081\"\n",
      "t.toml");
  ASSERT_TRUE(ok.config) << ok.error;
  EXPECT_EQ(ok.config->http.listen, "127.0.0.1:8080");
  EXPECT_EQ(ok.config->http.token, "long-enough");
  EXPECT_EQ(ok.config->tcp.listen, "localhost:8081");
  EXPECT_TRUE(parse_config("", "t.toml").config->http.listen.empty());  // off by default
  EXPECT_NE(config_error("[http]\nlisten = \"8080\"\n").find("t.toml:2: http.listen"),
            std::string::npos);
  EXPECT_NE(config_error("[tcp]\nlisten = \"cell-pc:8081\"\n").find("tcp.listen"),
            std::string::npos);
  EXPECT_NE(config_error("[http]\nlisten = \"127.0.0.1:70000\"\n").find("port"), std::string::npos);
  EXPECT_NE(config_error("[http]\ntoken = \"short\"\n").find("http.token"), std::string::npos);
  EXPECT_NE(config_error("[http]\ntoken = \"has a space\"\n").find("http.token"),
            std::string::npos);
  EXPECT_NE(config_error("[http]\nlisten = \"127.0.0.1:1\"\n[tcp]\nlisten = \"127.0.0.1:1\"\n")
                .find("tcp.listen"),
            std::string::npos);
  EXPECT_NE(config_error("[http]\nport = 8080\n").find("http.port: unknown field"),
            std::string::npos);
  EXPECT_NE(config_error("[spool]\npictures = 1\n").find("spool.pictures"), std::string::npos);
}

TEST(RequestFromJson, OnlyKindIsRequiredAndMistypedFieldsAreNamed) {
  ScanRequest r;
  std::string why;
  ASSERT_TRUE(request_from_json({{"kind", "object"}, {"model", "sphere"}}, r, &why)) << why;
  EXPECT_EQ(r.kind, DetectKind::kObject);
  EXPECT_EQ(r.model, "sphere");
  EXPECT_TRUE(r.id.empty());
  EXPECT_EQ(r.instances, 1);
  ASSERT_TRUE(request_from_json(
      {{"kind", "bore"}, {"bore", {{"radius_mm", 6}, {"plane_normal", {0, 0, 1}}}}}, r, &why));
  EXPECT_DOUBLE_EQ(r.bore.radius_mm, 6.0);
  EXPECT_TRUE(r.bore.axis.isApprox(Eigen::Vector3d::UnitZ()));  // the default kept
  ASSERT_TRUE(r.bore.plane_normal);
  EXPECT_FALSE(request_from_json({{"model", "sphere"}}, r, &why));
  EXPECT_NE(why.find("kind"), std::string::npos);
  EXPECT_FALSE(request_from_json({{"kind", "bore"}, {"bore", {{"radius_mm", "6"}}}}, r, &why));
  EXPECT_FALSE(request_from_json({{"kind", "screw"}}, r, &why));
  EXPECT_FALSE(request_from_json(nlohmann::json::array({1, 2}), r, &why));
}

TEST(AnswerFor, NotFoundIsAnAnswerBusyTimeoutAndErrorsAreNot) {
  ScanRequest req;
  req.id = "x";
  DetectionResult found = DetectionResult::error(req, "");
  found.found = true;
  EXPECT_EQ(answer_for(found).status, api::Status::kOk);
  const auto status = [&](const std::string& reason) {
    return answer_for(DetectionResult::error(req, reason)).status;
  };
  EXPECT_EQ(status(std::string(to_string(BoreReason::kEmptyRoi))), api::Status::kOk);
  EXPECT_EQ(status("busy: 4 requests queued"), api::Status::kBusy);
  EXPECT_EQ(status("scan timeout: not complete after 1.0 s"), api::Status::kTimeout);
  EXPECT_EQ(status("detection timeout: no result after 1.0 s"), api::Status::kTimeout);
  EXPECT_EQ(status("bad request: bore_radius must be > 0"), api::Status::kBadRequest);
  EXPECT_EQ(status("scan failed: css: no device"), api::Status::kError);
  const api::Answer a = answer_for(DetectionResult::error(req, "daemon stopping"));
  EXPECT_EQ(a.body["error"], "daemon stopping");
  EXPECT_EQ(a.body["request_id"], "x");
}

class NullSink : public ResultSink {
 public:
  void on_cloud(const ScanRequest&, const PointCloud&) override {}
  void on_result(const DetectionResult&) override { ++results; }
  void on_state(LifecycleState, const std::string&, const std::string&, std::size_t) override {}
  int results = 0;
};

DetectionResult result_of(const std::string& id) {
  ScanRequest req;
  req.id = id;
  return DetectionResult::error(req, "scan failed: test");
}

TEST(ResultBoard, WaitersGetTheirOwnNewResultAndOldOnesAreForgotten) {
  NullSink next;
  ResultBoard board(next, 3);
  EXPECT_FALSE(board.wait_for("a", std::chrono::milliseconds(1)));
  board.on_result(result_of("a"));  // an older result of the same id
  ASSERT_TRUE(board.reserve("a"));
  EXPECT_FALSE(board.reserve("a"));  // still running
  DetectionResult out;
  EXPECT_EQ(board.find("a", &out), ResultBoard::Lookup::kPending);
  auto waiter =
      std::async(std::launch::async, [&] { return board.wait_for("a", std::chrono::seconds(10)); });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  DetectionResult fresh = result_of("a");
  fresh.reason = "fresh";
  board.on_result(fresh);
  const auto got = waiter.get();
  ASSERT_TRUE(got);
  EXPECT_EQ(got->reason, "fresh");
  EXPECT_EQ(next.results, 2);  // every result is forwarded to DDS
  for (const char* id : {"b", "c", "d"}) board.on_result(result_of(id));
  EXPECT_EQ(board.find("a", &out), ResultBoard::Lookup::kUnknown);  // keep = 3
  const auto latest = board.latest(10);
  ASSERT_EQ(latest.size(), 3u);
  EXPECT_EQ(latest[0].request_id, "d");
  EXPECT_EQ(board.generation(), 5u);
  ASSERT_TRUE(board.reserve("e"));
  auto stopping =
      std::async(std::launch::async, [&] { return board.wait_for("e", std::chrono::seconds(10)); });
  board.close();
  EXPECT_FALSE(stopping.get());
}

}  // namespace service_backend_test
}  // namespace rangefit::daemon
