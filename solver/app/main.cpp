// rbla: the command-line program. Thin by design: every step is a library call the tests make
// too; the commands are in commands.hpp, what they share in cli.hpp (with the exit codes).
#include "commands.hpp"

#include "io/atomic_file.hpp"
#include "rbla/conic/problem.hpp"

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <new>
#include <vector>

namespace {
/// Ends the run without the libraries' exit handlers: OpenBLAS's joins its server thread, which
/// under an address-space limit may be retrying the malloc of its work buffer forever (the run
/// then hung at exit after printing this message).
[[noreturn]] void end_out_of_memory(const std::string& reason) {
  std::cerr << "rbla: out of memory" << (reason.empty() ? "" : ": " + rbla::cli::shown(reason)) << "\n";
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  std::_Exit(rbla::cli::kSolverFailure);
}
}  // namespace

int main(int argc, char** argv) {
  using namespace rbla::cli;
  // A reader that goes away (`rbla solve m.json -o - | head`) is a write error with a message,
  // not a silent death by SIGPIPE; an interrupted write leaves no temporary file behind.
  std::signal(SIGPIPE, SIG_IGN);
  rbla::io::remove_temporary_files_on_signals();
  CLI::App app{"rbla: rigid block limit analysis of masonry structures"};
  app.set_version_flag("--version", std::string("rbla ") + RBLA_VERSION);
  app.require_subcommand(1);
  CommonOptions options;
  const std::vector<Command> commands = {
      add_solve(app, options),
      add_validate(app, options),
      add_info(app, options),
      add_worst_direction(app, options),
      add_worst_settlement(app, options),
      add_critical_friction(app, options),
      add_sweep(app, options, std::vector<std::string>(argv, argv + argc))};

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kUsage;
  }

  for (const Command& command : commands) {
    if (!*command.app) continue;
    const std::string refused = refused_option_value(*command.app);
    if (refused.empty()) break;
    std::cerr << "rbla: " << shown(refused) << "\n";
    return kUsage;
  }
  try {
    for (const Command& command : commands) {
      if (*command.app) return command.run();
    }
  } catch (const UsageError& error) {
    std::cerr << "rbla: " << shown(error.what()) << "\n";
    return kUsage;
  } catch (const rbla::model::ModelError& error) {
    return report_invalid(error);
  } catch (const rbla::io::FileError& error) {
    return report_file_error(error);
  } catch (const rbla::conic::ConicResourceError& error) {
    end_out_of_memory(error.what());
  } catch (const std::bad_alloc&) {
    end_out_of_memory("");
  } catch (const std::exception& error) {
    // Anything else ends the run with its reason, never with an abort.
    std::cerr << "rbla: " << shown(error.what()) << "\n";
    return kSolverFailure;
  }
  return kUsage;
}
