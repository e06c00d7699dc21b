// `rangefit request` exit codes against a running service: 0 found, 2 not found (a detector
// said no), 1 error (bad request, no daemon). The replayed scan is a synthetic bore plate.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>

#include "daemon/rangefitd/service.hpp"
#include "daemon/service/result_outcome.hpp"
#include "detect/bore/bore_result.hpp"
#include "detect/learn/model_learning.hpp"
#include "detect/object/object_detector.hpp"
#include "io/ply.hpp"
#include "test/daemon/replay_service.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit::daemon {
namespace request_exit_code_test {
namespace fs = std::filesystem;

TEST(ResultOutcome, DetectorReasonsAreNotFoundAndEverythingElseIsAnError) {
  DetectionResult r;
  r.found = true;
  EXPECT_EQ(exit_code_of(r), 0);
  r.found = false;
  for (const auto* reason : {"too few entrance-plane points to fit a plane", "not confirmed",
                             "parts not linked", "no valid point within the region of interest"}) {
    r.reason = reason;
    EXPECT_EQ(exit_code_of(r), 2) << reason;
  }
  r.reason = std::string(to_string(BoreReason::kFitFailed));
  EXPECT_EQ(exit_code_of(r), 2);
  // Learning: the scan showed no object, or not the second part of a two-part one.
  for (const LearnReason why : {LearnReason::kNoObject, LearnReason::kSecondPartNotSeen}) {
    r.reason = to_string(why);
    EXPECT_EQ(exit_code_of(r), 2) << r.reason;
  }
  for (const std::string& reason :
       {std::string("bad request: unknown sensor \"x\""), std::string("scan failed: css: gone"),
        std::string("busy: 4 requests queued"), std::string(to_string(BoreReason::kBadPrior)),
        std::string(to_string(DetectReason::kInvalidModel)), std::string()}) {
    r.reason = reason;
    EXPECT_EQ(exit_code_of(r), 1) << reason;
  }
}

#ifdef RANGEFIT_CLI_PATH
int run_cli(const std::string& args, const fs::path& out) {
  const std::string cmd =
      std::string(RANGEFIT_CLI_PATH) + " request " + args + " > " + out.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(RequestCommand, ExitsZeroWhenFoundTwoWhenNotFoundOneOnABadRequest) {
  const fs::path dir = test::fresh_test_dir("rangefit_request_exit_test");
  sim::SyntheticBoreOptions opt;
  opt.radius = 5.0;
  opt.seed = 7;
  const auto scan = sim::make_synthetic_bore(opt);
  io::write_ply(dir / "plate.ply", scan.cloud);
  const DaemonConfig config = test::replay_css_config(dir, dir / "plate.ply");
  hal::MonotonicClock clock;
  Service service(config, clock);
  test::ServiceLoop loop(service);

  const std::string domain = "--domain " + std::to_string(config.dds.domain_id) + " --timeout 60";
  const Eigen::Vector3d e = scan.truth.entrance;
  std::ostringstream found;
  found << "bore " << domain << " --position " << e.x() << " " << e.y() << " " << e.z()
        << " --axis 0 0 1 --radius 5";
  EXPECT_EQ(run_cli(found.str(), dir / "found.out"), 0);
  // 300 mm beside the plate: the detector runs and finds nothing there.
  std::ostringstream elsewhere;
  elsewhere << "bore " << domain << " --position " << e.x() + 300 << " " << e.y() << " " << e.z()
            << " --axis 0 0 1 --radius 5";
  EXPECT_EQ(run_cli(elsewhere.str(), dir / "elsewhere.out"), 2);
  EXPECT_EQ(run_cli(found.str() + " --sensor nosuch", dir / "bad.out"), 1);
  fs::remove_all(dir);
}
#endif

}  // namespace request_exit_code_test
}  // namespace rangefit::daemon
