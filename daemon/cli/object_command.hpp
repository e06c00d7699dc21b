#pragma once
// `rangefit object`: superquadric object detection (thesis ch. 5) on a scan file.

#include <CLI/CLI.hpp>

namespace rangefit::cli {

void add_object_command(CLI::App& app, int* exit_code);

}  // namespace rangefit::cli
