#pragma once
// Option conventions every subcommand shares: "-" for standard input/output, and 3-vectors
// written X,Y,Z (one token; "X Y Z" as three tokens is accepted too where a command always
// took it).

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace rangefit::cli {

// --cloud check: an existing file, or "-" for standard input.
inline CLI::Validator cloud_input() {
  return CLI::Validator(
      [](std::string& value) { return value == "-" ? std::string() : CLI::ExistingFile(value); },
      "FILE|-", "existing file or - (stdin)");
}

// A 3-vector option stored in `values`: "X,Y,Z" or "X Y Z"; exactly three numbers.
inline CLI::Option* add_vector_option(CLI::App* cmd, const std::string& name,
                                      std::vector<double>& values, const std::string& help) {
  return cmd->add_option(name, values, help)->expected(3)->delimiter(',')->type_name("NUM");
}

}  // namespace rangefit::cli
