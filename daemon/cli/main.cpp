// rangefit: offline detection on scan files, simulation and replay of spooled scans.
#include <exception>
#include <iostream>

#include "daemon/cli/commands.hpp"
#include "daemon/cli/render_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "rangefit - find bore holes and objects in range scans by fitting geometric models.\n"
      "Units: millimetres and radians. Exit codes: 0 found, 2 not found, 1 bad input."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("rangefit ") + RANGEFIT_VERSION);
  int exit_code = rangefit::cli::kExitOk;
  // Subcommands (one file each in daemon/cli/):
  rangefit::cli::add_bore_command(app, &exit_code);
  rangefit::cli::add_object_command(app, &exit_code);
  rangefit::cli::add_learn_command(app, &exit_code);
  rangefit::cli::add_request_command(app, &exit_code);
  rangefit::cli::add_watch_command(app, &exit_code);
  rangefit::cli::add_models_command(app, &exit_code);
  rangefit::cli::add_replay_command(app, &exit_code);
#ifdef RANGEFIT_WITH_SIM
  rangefit::cli::add_simulate_command(app, &exit_code);
#endif
  rangefit::cli::add_render_command(app, &exit_code);
  rangefit::cli::add_calibrate_command(app, &exit_code);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : rangefit::cli::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "rangefit: " << e.what() << "\n";
    return rangefit::cli::kExitBadInput;
  }
  return exit_code;
}
