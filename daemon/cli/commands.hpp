#pragma once
// Each subcommand of `rangefit` lives in its own file and registers itself here.
// Exit codes shared by all subcommands: 0 found/success, 2 not found, 1 bad input or error.

#include <CLI/CLI.hpp>

namespace rangefit::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;
inline constexpr int kExitNotFound = 2;

// Each add_* function adds one subcommand to app; the subcommand's callback stores its exit code
// in *exit_code.
void add_request_command(CLI::App& app, int* exit_code);  // request_command.cpp
void add_watch_command(CLI::App& app, int* exit_code);  // watch_command.cpp
void add_models_command(CLI::App& app, int* exit_code);  // models_command.cpp
void add_replay_command(CLI::App& app, int* exit_code);  // replay_command.cpp
void add_simulate_command(CLI::App& app, int* exit_code);  // simulate_command.cpp
void add_bore_command(CLI::App& app, int* exit_code);  // bore_command.cpp
void add_object_command(CLI::App& app, int* exit_code);  // object_command.cpp
void add_learn_command(CLI::App& app, int* exit_code);  // learn_command.cpp
void add_calibrate_command(CLI::App& app, int* exit_code);  // calibrate_command.cpp
}  // namespace rangefit::cli
