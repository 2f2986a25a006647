// Runs the rbla program (RBLA_BINARY, set by tests/CMakeLists.txt) with a shell command line and
// captures what it prints, for the tests of the command-line interface.
#pragma once

#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <string>

namespace rbla::testing {

struct RunResult {
  int exit_code = -1;  // -1 when rbla did not exit normally (a signal)
  std::string output;  // standard output and standard error together (run_rbla)
  std::string standard_output;  // run_rbla_with only
  std::string standard_error;   // run_rbla_with only
};

inline RunResult run_rbla(const std::string& arguments) {
  const std::string command = std::string(RBLA_BINARY) + " " + arguments + " 2>&1";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

/// How run_rbla_with runs the program.
struct RunOptions {
  std::string arguments;              ///< after the program's name, in shell syntax (redirections too)
  std::string input_command;          ///< when given, "INPUT_COMMAND | rbla ARGUMENTS"
  std::uint64_t address_space = 0;    ///< RLIMIT_AS in bytes for the whole command line (0: none)
  std::uint64_t file_size = 0;        ///< RLIMIT_FSIZE in bytes (0: none); SIGXFSZ is ignored, so a
                                      ///< write beyond it fails with EFBIG instead of killing
  std::uint64_t cpu_seconds = 0;      ///< RLIMIT_CPU (0: none): a run that spins is killed
                                      ///< (SIGXCPU) and fails its test instead of hanging it
};

/// True when the program was built with AddressSanitizer, which reserves terabytes of address
/// space and so cannot run under RLIMIT_AS.
inline bool built_with_address_sanitizer() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return true;
#else
  return false;
#endif
#else
  return false;
#endif
}

/// Runs `/bin/sh -c "[INPUT |] rbla ARGUMENTS"` in a child with the limits asked for (set with
/// setrlimit in the child before exec) and returns its exit code, standard output and standard
/// error separately (`output` has both).
inline RunResult run_rbla_with(const RunOptions& options) {
  const std::string command =
      (options.input_command.empty() ? std::string() : options.input_command + " | ") + RBLA_BINARY + " " +
      options.arguments;
  RunResult result;
  int out[2], err[2];
  if (::pipe(out) != 0) return result;
  if (::pipe(err) != 0) return result;
  const pid_t child = ::fork();
  if (child < 0) return result;
  if (child == 0) {
    ::dup2(out[1], STDOUT_FILENO);
    ::dup2(err[1], STDERR_FILENO);
    for (int fd : {out[0], out[1], err[0], err[1]}) ::close(fd);
    if (options.address_space) {
      const rlimit limit{options.address_space, options.address_space};
      ::setrlimit(RLIMIT_AS, &limit);
    }
    if (options.cpu_seconds) {
      const rlimit limit{options.cpu_seconds, options.cpu_seconds};
      ::setrlimit(RLIMIT_CPU, &limit);
    }
    if (options.file_size) {
      std::signal(SIGXFSZ, SIG_IGN);  // kept across exec
      const rlimit limit{options.file_size, options.file_size};
      ::setrlimit(RLIMIT_FSIZE, &limit);
    }
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(out[1]);
  ::close(err[1]);
  std::array<pollfd, 2> fds{{{out[0], POLLIN, 0}, {err[0], POLLIN, 0}}};
  std::array<std::string*, 2> into{&result.standard_output, &result.standard_error};
  int open_streams = 2;
  std::array<char, 4096> buffer{};
  while (open_streams > 0) {
    if (::poll(fds.data(), fds.size(), -1) < 0) break;
    for (std::size_t k = 0; k < fds.size(); ++k) {
      if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = ::read(fds[k].fd, buffer.data(), buffer.size());
      if (n > 0) {
        into[k]->append(buffer.data(), static_cast<std::size_t>(n));
      } else {
        ::close(fds[k].fd);
        fds[k].fd = -1;
        --open_streams;
      }
    }
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.output = result.standard_output + result.standard_error;
  return result;
}

}  // namespace rbla::testing
