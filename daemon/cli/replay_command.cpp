#include "daemon/cli/replay_command.hpp"

#include <iostream>

#include "daemon/cli/commands.hpp"
#include "daemon/service/json_codec.hpp"
#include "daemon/service/model_detector.hpp"
#include "daemon/service/result_picture.hpp"
#include "daemon/service/spool.hpp"

namespace rangefit::cli {

void add_replay_command(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("replay", "re-run the detection of a rangefitd spool entry");
  static std::string entry, config_path, png;
  cmd->add_option("entry", entry, "spool entry directory")->required();
  cmd->add_option("--config", config_path,
                  "daemon config with the detection settings and models "
                  "(default: built-in defaults)");
  cmd->add_option("--png", png,
                  "also draw the replayed detection over the scan as a PNG (object results need "
                  "--config for their model's shape)");
  cmd->callback([exit_code] {
    std::string why;
    const auto spooled = daemon::read_spool_entry(entry, &why);
    if (!spooled) {
      std::cerr << "rangefit replay: " << why << "\n";
      *exit_code = kExitBadInput;
      return;
    }
    daemon::DaemonConfig config;
    if (!config_path.empty()) {
      auto loaded = daemon::load_config(config_path);
      if (!loaded.config) {
        std::cerr << "rangefit replay: " << loaded.error << "\n";
        *exit_code = kExitBadInput;
        return;
      }
      config = *loaded.config;
    }
    daemon::ModelDetector detector(config);
    // The spool keeps the cloud and the request, not the sensor: detection without it.
    daemon::DetectionResult result = detector.detect(spooled->cloud, spooled->request, {}, {});
    result.request_id = spooled->request.id;
    result.kind = spooled->request.kind;
    result.model = spooled->request.model;
    result.num_points = spooled->cloud.size();
    std::cout << nlohmann::json{{"spooled", daemon::to_json(spooled->result)},
                                {"replayed", daemon::to_json(result)}}
                     .dump(2)
              << "\n";
    *exit_code = result.found ? kExitOk : kExitNotFound;
    if (!png.empty()) {
      const daemon::ObjectModelConfig* model = config.object(result.model);
      if (!daemon::write_result_picture(png, spooled->cloud, result,
                                        model ? &model->model : nullptr, &why)) {
        std::cerr << "rangefit replay: --png: " << why << "\n";
        *exit_code = kExitBadInput;
      }
    }
  });
}

}  // namespace rangefit::cli
