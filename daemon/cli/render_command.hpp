#pragma once
// `rangefit render`: a picture of a scan file and, optionally, a detection result over it.

#include <CLI/CLI.hpp>

namespace rangefit::cli {

void add_render_command(CLI::App& app, int* exit_code);

}  // namespace rangefit::cli
