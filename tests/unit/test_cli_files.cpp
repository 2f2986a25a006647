// The rbla program and the file system (issue 19): what it writes into (FIFOs, character
// devices, links, files with their modes, its own input), what it reads from (directories,
// devices, endless streams, enormous inputs) and what its messages quote. Every FIFO, link and
// device node is made in a temporary folder; nothing under /dev is touched.
#include "io/load_model.hpp"
#include "model/errors.hpp"
#include "support/cli_runner.hpp"
#include "support/model_builder.hpp"
#include "support/temp_folder.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace fs = std::filesystem;
using namespace rbla::testing;

namespace {

constexpr std::uint64_t kOneGiB = 1ull << 30;

class CliFiles : public TempFolderTest {
 protected:
  CliFiles() : TempFolderTest("rbla_files") {}
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }
  static std::string read(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  static mode_t mode_of(const std::string& file) {
    struct stat info {};
    return ::lstat(file.c_str(), &info) == 0 ? info.st_mode : 0;
  }
  /// One 1 x 1 x 2 block on a fixed base, seismic along +x: alpha = b/h = 0.5.
  static std::string model_text() {
    json m = model_with(json::array({box_block("base", -1, -1, -1, 2, 2, 0, "fixed"), box_block("B1", 0, 0, 0, 1, 1, 2)}));
    m["analysis"] = {{"seismic", {{"direction", {1, 0, 0}}}}};
    return m.dump(1);
  }
  std::string model() const { return write("m.json", model_text()); }
  /// No temporary file is left in the folder.
  void expect_no_temporary_files() const {
    for (const auto& entry : fs::directory_iterator(dir_)) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
    }
  }
  /// A device node like the null device (1, 3) in the folder; empty when this system forbids it.
  std::string null_device(const std::string& name) const {
    if (::geteuid() != 0 || ::mknod(path(name).c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) return {};
    return path(name);
  }
};

bool is_json_result(const std::string& text) {
  try {
    return json::parse(text).contains("status");
  } catch (const json::exception&) {
    return false;
  }
}

}  // namespace

// ---- Output: what a path leads to decides how it is written -------------------------------------

TEST_F(CliFiles, ResultStreamsIntoAFifoThatStaysAFifo) {
  const std::string fifo = path("result.fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0) << std::strerror(errno);
  // The reading end is open before rbla starts, so its open for writing does not wait; the result
  // (a few kB) fits the pipe's buffer.
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  const auto r = run_rbla("solve -q " + model() + " -o " + fifo);
  std::string received;
  char buffer[4096];
  for (ssize_t n; (n = ::read(reader, buffer, sizeof buffer)) > 0;) received.append(buffer, static_cast<std::size_t>(n));
  ::close(reader);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(S_ISFIFO(mode_of(fifo))) << "the FIFO was replaced";
  EXPECT_TRUE(is_json_result(received)) << received.substr(0, 200);
  expect_no_temporary_files();
}

TEST_F(CliFiles, OutputsStreamIntoACharacterDeviceThatStaysOne) {
  const std::string null = null_device("null");
  if (null.empty()) GTEST_SKIP() << "cannot make a device node here (needs root and mknod)";
  const auto r = run_rbla("solve -q " + model() + " -o " + null + " --dump-problem " + null);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(S_ISCHR(mode_of(null))) << "the device node was replaced by a regular file";
  expect_no_temporary_files();
}

TEST_F(CliFiles, StandardOutputCarriesTheResultAlone) {
  // "-", and standard output by a name: /proc/self/fd/1 is a link whose text ("pipe:[123]") names
  // no file, so it must be written as what it leads to, not followed by hand.
  for (const std::string& output : {std::string("-"), std::string("/proc/self/fd/1")}) {
    const auto r = run_rbla_with({"solve " + model() + " -o " + output, "", 0, 0});
    EXPECT_EQ(r.exit_code, 0) << output << ": " << r.standard_error;
    EXPECT_TRUE(is_json_result(r.standard_output)) << output << ": " << r.standard_output.substr(0, 200);
    EXPECT_NE(r.standard_error.find("Collapse at load multiplier alpha = 0.5"), std::string::npos) << r.standard_error;
  }
}

TEST_F(CliFiles, SymbolicLinkIsFollowedAndItsTargetReplacedWithItsMode) {
  const std::string target = write("target.json", "old");
  ASSERT_EQ(::chmod(target.c_str(), 0600), 0);
  fs::create_symlink("target.json", path("link.json"));  // relative, as links usually are
  const auto r = run_rbla("solve -q " + model() + " -o " + path("link.json"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(S_ISLNK(mode_of(path("link.json")))) << "the link itself was replaced";
  EXPECT_TRUE(is_json_result(read(target))) << read(target).substr(0, 100);
  EXPECT_EQ(mode_of(target) & 07777, 0600u);
  expect_no_temporary_files();
}

TEST_F(CliFiles, DanglingLinkGetsItsTargetCreated) {
  fs::create_directories(path("out"));
  fs::create_symlink("out/new.json", path("dangling.json"));
  const auto r = run_rbla("solve -q " + model() + " -o " + path("dangling.json"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(S_ISLNK(mode_of(path("dangling.json"))));
  EXPECT_TRUE(is_json_result(read(path("out/new.json"))));
}

TEST_F(CliFiles, ReplacedFilesKeepTheirModes) {
  const std::string result = write("r.json", "old"), problem = write("p.cbf", "old");
  fs::create_directories(path("svg"));
  const std::string picture = write("svg/mechanism.svg", "old");
  ASSERT_EQ(::chmod(result.c_str(), 0600), 0);
  ASSERT_EQ(::chmod(problem.c_str(), 0640), 0);
  ASSERT_EQ(::chmod(picture.c_str(), 0604), 0);
  const auto r = run_rbla("solve -q " + model() + " -o " + result + " --dump-problem " + problem + " --svg " + path("svg"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(mode_of(result) & 07777, 0600u);
  EXPECT_EQ(mode_of(problem) & 07777, 0640u);
  EXPECT_EQ(mode_of(picture) & 07777, 0604u);
  EXPECT_NE(read(problem), "old");
  EXPECT_NE(read(picture), "old");
}

TEST_F(CliFiles, AnOutputThatIsTheInputIsRefusedHoweverSpelled) {
  const std::string m = model();
  const std::string text = read(m);
  fs::create_directories(path("sub"));
  fs::create_symlink("m.json", path("symlink.json"));
  fs::create_hard_link(m, path("hardlink.json"));
  fs::create_directories(path("svg"));
  fs::create_symlink("../m.json", path("svg/mechanism.svg"));
  const std::string relative_detour = (dir_ / "sub" / ".." / "." / "m.json").string();
  const std::vector<std::string> cases = {
      "solve -q " + m + " -o " + m,
      "solve -q " + m + " -o " + relative_detour,
      "solve -q " + m + " -o " + path("symlink.json"),
      "solve -q " + path("symlink.json") + " -o " + m,
      "solve -q " + m + " -o " + path("hardlink.json"),
      "solve -q - -o " + m + " < " + m,
      "solve -q " + m + " --dump-problem " + relative_detour,
      "solve -q " + m + " --svg " + path("svg"),
      "info -q " + m + " -o " + path("symlink.json"),
  };
  for (const std::string& arguments : cases) {
    const auto r = run_rbla(arguments);
    EXPECT_EQ(r.exit_code, 4) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find("it is the model being read"), std::string::npos) << arguments << "\n" << r.output;
    EXPECT_EQ(r.output.find("Collapse"), std::string::npos) << "refused only after the analysis: " << arguments;
    EXPECT_EQ(read(m), text) << "the model was overwritten by: " << arguments;
  }
  expect_no_temporary_files();
}

TEST_F(CliFiles, TwoOutputsThatAreOneFileAreRefused) {
  const std::string m = model();
  fs::create_symlink("r.json", path("r_link.json"));
  for (const std::string& arguments : {"solve -q " + m + " -o " + path("r.json") + " --dump-problem " + path("r_link.json"),
                                       "solve -q " + m + " -o - --dump-problem -"}) {
    const auto r = run_rbla(arguments);
    EXPECT_EQ(r.exit_code, 4) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find("one output would overwrite the other"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(path("r.json")));
}

TEST_F(CliFiles, DirectoriesAndSocketsAreRefusedAsOutputs) {
  const std::string m = model();
  fs::create_directories(path("folder"));
  const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(s, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::string socket_path = path("sock");
  ASSERT_LT(socket_path.size(), sizeof address.sun_path);
  std::strcpy(address.sun_path, socket_path.c_str());
  ASSERT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&address), sizeof address), 0) << std::strerror(errno);
  const auto to_folder = run_rbla("solve -q " + m + " -o " + path("folder"));
  EXPECT_EQ(to_folder.exit_code, 4) << to_folder.output;
  EXPECT_NE(to_folder.output.find("cannot write '" + path("folder") + "': it is a directory"), std::string::npos)
      << to_folder.output;
  const auto to_socket = run_rbla("solve -q " + m + " --dump-problem " + socket_path);
  EXPECT_EQ(to_socket.exit_code, 4) << to_socket.output;
  EXPECT_NE(to_socket.output.find("it is a socket"), std::string::npos) << to_socket.output;
  EXPECT_TRUE(S_ISSOCK(mode_of(socket_path)));
  ::close(s);
}

TEST_F(CliFiles, AFailedWriteLeavesTheOldFileAsItWas) {
  const std::string result = write("r.json", "the previous result");
  ASSERT_EQ(::chmod(result.c_str(), 0640), 0);
  // A file-size limit of 1000 bytes: writing the result (several kB) fails with EFBIG half-way.
  const auto r = run_rbla_with({"solve -q " + model() + " -o " + result, "", 0, 1000});
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("cannot write '" + result + "'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(std::strerror(EFBIG)), std::string::npos) << r.output;
  EXPECT_EQ(read(result), "the previous result");
  EXPECT_EQ(mode_of(result) & 07777, 0640u);
  expect_no_temporary_files();
}

/// rbla run as a user other than root (nobody, through util-linux's setpriv, when the tests run as
/// root, which may replace any file), so that file permissions apply.
RunResult run_unprivileged(const std::string& arguments) {
  const std::string as = ::geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups " : "";
  std::string command = as + RBLA_BINARY + " " + arguments + " 2>&1";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// A file rbla may not write (read-only, or another user's) is not replaced, though the folder
// would let a rename put a new file in its place; a folder it may not write into is said before
// the analysis.
TEST_F(CliFiles, AFileWeMayNotWriteIsNotReplaced) {
  ASSERT_EQ(::chmod(dir_.c_str(), 0777), 0);
  const std::string m = model();
  const std::string read_only = write("read_only.json", "kept");
  ASSERT_EQ(::chmod(read_only.c_str(), 0444), 0);
  auto r = run_unprivileged("solve -q " + m + " -o " + read_only);
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("may not be written"), std::string::npos) << r.output;
  EXPECT_EQ(read(read_only), "kept");
  ASSERT_EQ(::mkdir(path("closed").c_str(), 0555), 0);
  r = run_unprivileged("solve " + m + " -o " + path("closed/r.json"));
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("cannot write into its folder"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("Collapse"), std::string::npos) << "refused before the analysis";
  expect_no_temporary_files();
}

TEST_F(CliFiles, MissingFoldersAreFileErrorsFoundBeforeTheAnalysis) {
  const std::string m = model();
  const std::string file = write("plain.txt", "x");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"-o " + path("none/r.json"), "its folder '" + path("none") + "' does not exist"},
      {"--dump-problem " + path("none/p.cbf"), "its folder '" + path("none") + "' does not exist"},
      {"--svg " + file, "cannot write into '" + file + "': it is not a folder"},
      {"-o " + file + "/r.json", "cannot write '" + file + "/r.json': Not a directory"},
      // The picture folder to be made where the result goes: it became a folder, the result failed.
      {"-o " + path("r.json") + " --svg " + path("r.json"), "they are the same file"},
  };
  for (const auto& [arguments, words] : cases) {
    const auto r = run_rbla("solve -q " + m + " " + arguments);
    EXPECT_EQ(r.exit_code, 4) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << arguments << "\n" << r.output;
    EXPECT_EQ(r.output.find("Collapse"), std::string::npos) << arguments;
  }
}

// ---- Input: a regular file, a pipe or '-', and no more than the limits ---------------------------

// JSON text holds no NUL byte, and the parser took one for the end of the text: a model followed
// by a NUL and anything at all was valid. From a file and from standard input.
TEST_F(CliFiles, ANulByteIsMalformedJsonNotTheEndOfTheText) {
  const std::string m = write("nul.json", model_text() + std::string(1, '\0') + "{{{{ junk");
  for (const std::string& arguments : {"validate " + m, "validate - < " + m}) {
    const auto r = run_rbla(arguments);
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find("holds a NUL byte at byte " + std::to_string(model_text().size())), std::string::npos)
        << r.output;
  }
  EXPECT_THROW(rbla::io::load_model_text(model_text() + std::string(1, '\0')), rbla::model::ModelError);
}

TEST_F(CliFiles, ADirectoryAsTheModelIsAFileErrorNamingIt) {
  const auto r = run_rbla("validate " + dir_.string());
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("cannot read '" + dir_.string() + "': it is a directory"), std::string::npos) << r.output;
}

TEST_F(CliFiles, ACharacterDeviceAsTheModelIsRefusedUnread) {
  // An endless device (like the zero device, 1, 5), under a 1 GiB address-space cap: it must be
  // refused before it is read, not read until memory runs out.
  if (built_with_address_sanitizer()) GTEST_SKIP() << "AddressSanitizer cannot run under RLIMIT_AS";
  const std::string zero = path("zero");
  if (::geteuid() != 0 || ::mknod(zero.c_str(), S_IFCHR | 0666, makedev(1, 5)) != 0) {
    GTEST_SKIP() << "cannot make a device node here (needs root and mknod)";
  }
  const auto r = run_rbla_with({"validate " + zero, "", kOneGiB, 0});
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("cannot read '" + zero + "': it is a character device"), std::string::npos) << r.output;
}

TEST_F(CliFiles, AFifoAsTheModelIsRead) {
  const std::string fifo = path("model.fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const std::string text = model_text();
  std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << text; });
  const auto r = run_rbla("validate " + fifo);
  writer.join();
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("valid: 2 blocks"), std::string::npos) << r.output;
}

TEST_F(CliFiles, EndlessStandardInputEndsAtTheLimit) {
  if (built_with_address_sanitizer()) GTEST_SKIP() << "AddressSanitizer cannot run under RLIMIT_AS";
  const auto r = run_rbla_with({"validate - --max-input-bytes 1000000", "yes ' '", kOneGiB, 0});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("standard input is larger than the limit of 1000000 bytes of model JSON (raise it with "
                          "--max-input-bytes)"),
            std::string::npos)
      << r.output;
}

TEST_F(CliFiles, HundredMegabytesOfOpeningBracketsStayWithinMemory) {
  // Streamed through a pipe, never written to disk; 100 MB of '[' grew past 3 GB before limits.
  if (built_with_address_sanitizer()) GTEST_SKIP() << "AddressSanitizer cannot run under RLIMIT_AS";
  const auto r = run_rbla_with({"validate -", "yes '[' | tr -d '\\n' | head -c 100000000", kOneGiB / 4, 0});
  EXPECT_EQ(r.exit_code, 2) << r.output.substr(0, 1000);
  EXPECT_NE(r.output.find("deeper than the limit of 64 levels of nested arrays and objects (raise it with --max-depth)"),
            std::string::npos)
      << r.output.substr(0, 1000);
}

TEST_F(CliFiles, AnAddressSpaceLimitEndsTheRunWithOutOfMemoryNeverAHang) {
  // Under RLIMIT_AS, OpenBLAS retried the malloc of its 128 MiB work buffer forever at 100 % CPU:
  // the bundled wall hung at every limit from 100 to 300 MB. Each run must end, with the result
  // or with exit 3 and "out of memory"; RLIMIT_CPU turns a spin into a failure of this test.
  if (built_with_address_sanitizer()) GTEST_SKIP() << "AddressSanitizer cannot run under RLIMIT_AS";
  const std::string model = std::string(RBLA_SOURCE_DIR) + "/samples/wall_opening.json";
  int refused = 0, solved = 0;
  for (std::uint64_t megabytes = 100; megabytes <= 600; megabytes += 50) {
    const auto r = run_rbla_with({"solve " + model + " -o " + path("r.json"), "", megabytes << 20, 0, 60});
    SCOPED_TRACE(std::to_string(megabytes) + " MB: " + r.output.substr(0, 2000));
    if (r.exit_code == 0) {
      ++solved;
    } else {
      EXPECT_EQ(r.exit_code, 3);
      EXPECT_NE(r.output.find("out of memory"), std::string::npos);
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);  // the limits reach the factorisation...
  EXPECT_GT(solved, 0);   // ...and the largest lets it finish
}

// --dump-problem was written as soon as the problem was built, before the solve: SIGTERM during
// the solve left it replaced. It is now written after the solve, as the result is.
TEST_F(CliFiles, AnInterruptedSolveLeavesTheProblemDumpAsItWas) {
  // A 40 x 30 wall of bricks in running bond under non-associative friction: seconds of solves.
  json blocks = json::array({box_block("base", -1, -1, -1, 41, 1, 0, "fixed")});
  for (int row = 0; row < 30; ++row) {
    const double shift = row % 2 ? 0.5 : 0.0;
    for (int k = 0; k < 40; ++k) {
      blocks.push_back(box_block("b" + std::to_string(row) + "_" + std::to_string(k), k + shift, 0, row * 0.5,
                                 k + shift + 1, 0.5, row * 0.5 + 0.5));
    }
  }
  json m = model_with(blocks);
  m["analysis"] = {{"seismic", {{"direction", {1, 0, 0}}}}, {"friction_model", "non_associative"}};
  const std::string model = write("wall.json", m.dump());
  const std::string dump = write("p.cbf", "not ours to replace\n");
  const std::string log = path("log.txt");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(fd, STDERR_FILENO);
    ::execl(RBLA_BINARY, RBLA_BINARY, "solve", "-v", model.c_str(), "--dump-problem", dump.c_str(), "-o",
            path("r.json").c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Waits (a bound, not a timing) for the interior-point log's header: the solve is under way.
  for (int k = 0; k < 6000 && read(log).find("iter  primal obj") == std::string::npos; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(child, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "the run ended before the signal:\n" << read(log);
  EXPECT_EQ(read(dump), "not ours to replace\n");
  EXPECT_FALSE(fs::exists(path("r.json")));
  expect_no_temporary_files();
}

TEST_F(CliFiles, AHugeStringIsRefusedBeforeItIsWhole) {
  // The lexer gathered each string whole before its length was checked: a 200 MB string took
  // 400 MB and seconds. 250 MB of one string now ends at the limit within 256 MiB of address space.
  if (built_with_address_sanitizer()) GTEST_SKIP() << "AddressSanitizer cannot run under RLIMIT_AS";
  const auto r = run_rbla_with({"validate -", "{ printf '{\"title\": \"'; head -c 250000000 /dev/zero | tr '\\0' x; }",
                                kOneGiB / 4, 0});
  EXPECT_EQ(r.exit_code, 2) << r.output.substr(0, 1000);
  EXPECT_NE(r.output.find("/title: a string of more than 10000 bytes is longer than the limit of "
                          "10000 bytes in one string or property name (raise it with --max-string-bytes)"),
            std::string::npos)
      << r.output.substr(0, 1000);
}

TEST_F(CliFiles, AFileLargerThanTheLimitIsRefusedBeforeItIsRead) {
  // 300 MB without writing them: a sparse file.
  const std::string big = path("big.json");
  const int fd = ::open(big.c_str(), O_CREAT | O_WRONLY, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, 300'000'000), 0);
  ::close(fd);
  RunOptions options{"validate " + big, "", 0, 0};
  if (!built_with_address_sanitizer()) options.address_space = kOneGiB / 4;
  const auto r = run_rbla_with(options);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'" + big + "' is larger than the limit of 268435456 bytes of model JSON (raise it with "
                          "--max-input-bytes): it is 300000000 bytes"),
            std::string::npos)
      << r.output;
}

TEST_F(CliFiles, EachLimitIsAnOptionNamedInItsMessage) {
  json m = json::parse(model_text());
  const json square = json::array({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  m["interfaces"] = {{{"id", "a"}, {"blocks", {"base", "B1"}}, {"polygon", square}},
                     {{"id", "b"}, {"blocks", {"base", "B1"}}, {"polygon", {{0, 0, 0}, {0.5, 0, 0}, {0.5, 1, 0}, {0, 1, 0}}}}};
  const std::string file = write("m2.json", m.dump(2));  // over 1 kB
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"--max-blocks 1", "/blocks/1", "more than the limit of 1 blocks (raise it with --max-blocks)"},
      {"--max-vertices 12", "/blocks/1/vertices/4", "more than the limit of 12 vertices of all blocks together"},
      {"--max-interfaces 1", "/interfaces/1", "(raise it with --max-interfaces)"},
      {"--max-string-bytes 8", "/analysis/seismic",
       "a property name of 9 bytes (direction) is longer than the limit of 8 bytes"},
      {"--max-depth 3", "/analysis/seismic/direction", "deeper than the limit of 3 levels"},
      {"--max-input-bytes 1K", "(document)", "larger than the limit of 1024 bytes of model JSON"},
  };
  for (const auto& [option, pointer, words] : cases) {
    const auto r = run_rbla("validate -q " + file + " " + option);
    EXPECT_EQ(r.exit_code, 2) << option << "\n" << r.output;
    EXPECT_NE(r.output.find("  " + pointer + ": "), std::string::npos) << option << "\n" << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << option << "\n" << r.output;
  }
  EXPECT_EQ(run_rbla("validate -q " + file).exit_code, 0);
  EXPECT_EQ(run_rbla("validate -q " + file + " --max-depth 0").exit_code, 1);
  EXPECT_EQ(run_rbla("validate -q " + file + " --max-blocks 1000001").exit_code, 1);  // beyond the schema
}

// ---- Messages: what the user wrote is quoted escaped and cut --------------------------------------

TEST_F(CliFiles, ControlCharactersInTheModelCannotForgeALine) {
  json m = json::parse(model_text());
  m["loads"] = {{"live", {{{"block", "B1\n\x1b[31mrbla: FAKE ERROR\x1b[0m"}, {"force", {1, 0, 0}}}}}};
  m["blocks"][1]["label"] = "\x1b]0;title\x07";
  const auto r = run_rbla("solve " + write("ctrl.json", m.dump()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("\nrbla: FAKE"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no block has id 'B1\\u000A\\u001B[31mrbla: FAKE ERROR\\u001B[0m'"), std::string::npos)
      << r.output;
}

TEST_F(CliFiles, HugeNamesAndNumbersAreCutInMessages) {
  const std::string head = R"({"schema_version": "1.0.0", "units": {"length": "m"}, )";
  const std::string long_name = write("name.json", head + "\"" + std::string(10'000'000, 'x') + "\": 1}");
  const std::string long_number = write("number.json", head + "\"title\": 1" + std::string(10'000'000, '1') + "}");
  // The name is refused unread, at the object; the number is quoted cut.
  for (const auto& [file, said] : {std::pair{long_name, std::string("  (document): a property name of more than 10000 bytes")},
                                   std::pair{long_number, std::string("bytes in all")}}) {
    const auto r = run_rbla("validate " + file);
    EXPECT_EQ(r.exit_code, 2) << r.output.substr(0, 500);
    EXPECT_LT(r.output.size(), 1000u) << r.output.substr(0, 500);
    EXPECT_NE(r.output.find(said), std::string::npos) << r.output.substr(0, 500);
  }
}

TEST_F(CliFiles, PathsInMessagesAreEscaped) {
  const auto r = run_rbla("validate '" + path("no\nrbla: FAKE.json") + "'");
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_EQ(r.output.find("\nrbla: FAKE"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no\\u000Arbla: FAKE.json"), std::string::npos) << r.output;
}

TEST_F(CliFiles, MessagesThatMisledSayWhatIsWrong) {
  const json good = json::parse(model_text());
  {
    json m = good;  // 2^64 - 1 was validated as -1: "Expected number greater than or equal to 0"
    m["blocks"][1]["faces"][1][3] = 18446744073709551615ull;
    const auto r = run_rbla("validate -q " + write("index.json", m.dump()));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("/blocks/1/faces/1/3: expected an integer, found the number 1.8446744073709552e+19"),
              std::string::npos)
        << r.output;
  }
  {
    json m = good;  // its squared length underflows, but it is the direction +x
    m["analysis"]["seismic"]["direction"] = {1e-170, 0, 0};
    const auto r = run_rbla("solve -q " + write("tiny.json", m.dump()));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("Collapse at load multiplier alpha = 0.5"), std::string::npos) << r.output;
  }
  {
    json m = good;  // 4.0 is the integer 4 (JSON Schema draft 6 on)
    m["blocks"][1]["faces"][1] = {4.0, 5.0, 6.0, 7.0};
    std::string text = m.dump();
    const auto at = text.find("[4,5,6,7]");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 9, "[4.0,5.0,6.0,7.0]");
    const auto r = run_rbla("validate -q " + write("floats.json", text));
    EXPECT_EQ(r.exit_code, 0) << r.output;
  }
  {
    json m = good;  // was "(document): Object contains a property that could not be validated ..."
    m["Blocks"] = json::array();
    const auto r = run_rbla("validate -q " + write("unknown.json", m.dump()));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("  /Blocks: unknown property"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("(document)"), std::string::npos) << r.output;
  }
}
