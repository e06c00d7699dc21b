#pragma once
// `rangefit simulate`: scan a TOML scene with a simulated sensor (sim/), fuse the raw HAL streams
// into a world-frame cloud (fusion/) and write it plus a ground-truth JSON of the scene.

#include <CLI/CLI.hpp>

namespace rangefit::cli {

void add_simulate_command(CLI::App& app, int* exit_code);

}  // namespace rangefit::cli
