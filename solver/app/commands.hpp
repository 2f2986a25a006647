// The rbla commands. Each adds its subcommand and options to the program and returns how to run
// it; main.cpp parses the command line and runs the one given.
#pragma once

#include "cli.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace rbla::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Command add_solve(CLI::App& app, CommonOptions& options);
Command add_validate(CLI::App& app, CommonOptions& options);
Command add_info(CLI::App& app, CommonOptions& options);
Command add_worst_direction(CLI::App& app, CommonOptions& options);
Command add_worst_settlement(CLI::App& app, CommonOptions& options);
Command add_critical_friction(CLI::App& app, CommonOptions& options);
/// `command_line`: the program's arguments, which the sweep passes on to the tasks it starts.
Command add_sweep(CLI::App& app, CommonOptions& options, std::vector<std::string> command_line);

}  // namespace rbla::cli
