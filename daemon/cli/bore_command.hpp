#pragma once
// `rangefit bore`: detect a bore hole in a scan file from its CAD prior (thesis chapter 4).

#include <CLI/CLI.hpp>

namespace rangefit::cli {

void add_bore_command(CLI::App& app, int* exit_code);

}  // namespace rangefit::cli
