// io/atomic_file.hpp as a library: what a path resolves to, and that nothing is left half-written
// when the writer fails or the process is interrupted in the middle of a write.
#include "io/atomic_file.hpp"
#include "io/file_error.hpp"
#include "support/temp_folder.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;
using rbla::io::OutputKind;

namespace {

class OutputFile : public rbla::testing::TempFolderTest {
 protected:
  OutputFile() : TempFolderTest("rbla_output") {}
  static std::string read(const std::string& file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  std::size_t files_in_folder() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++n;
    return n;
  }
};

}  // namespace

TEST_F(OutputFile, PathsResolveToWhatIsThere) {
  std::ofstream(path("file")) << "x";
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0644), 0);
  fs::create_symlink("file", path("link"));
  fs::create_symlink("link", path("link_to_link"));
  EXPECT_EQ(rbla::io::resolve_output("-").kind, OutputKind::StandardOutput);
  EXPECT_EQ(rbla::io::resolve_output(path("fifo")).kind, OutputKind::Stream);
  const auto new_file = rbla::io::resolve_output(path("new"));
  EXPECT_EQ(new_file.kind, OutputKind::Replace);
  EXPECT_FALSE(new_file.identity.has_value());
  const auto through_links = rbla::io::resolve_output(path("link_to_link"));
  EXPECT_EQ(through_links.kind, OutputKind::Replace);
  EXPECT_EQ(through_links.target, path("file"));
  EXPECT_TRUE(through_links.identity.has_value());
  fs::create_symlink("loop_b", path("loop_a"));
  fs::create_symlink("loop_a", path("loop_b"));
  EXPECT_THROW(rbla::io::resolve_output(path("loop_a")), rbla::io::FileError);
  EXPECT_THROW(rbla::io::resolve_output(dir_.string()), rbla::io::FileError);
  EXPECT_THROW(rbla::io::resolve_output(path("missing/file")), rbla::io::FileError);
  EXPECT_THROW(rbla::io::resolve_output(""), rbla::io::FileError);
}

TEST_F(OutputFile, AWriterThatFailsLeavesTheTargetAndNoTemporaryFile) {
  std::ofstream(path("result.json")) << "before";
  EXPECT_THROW(rbla::io::write_output(path("result.json"),
                                      [](std::ostream& out) {
                                        out << std::string(100000, 'x');  // past the first buffer
                                        throw std::runtime_error("the writer failed");
                                      }),
               std::runtime_error);
  EXPECT_EQ(read(path("result.json")), "before");
  EXPECT_EQ(files_in_folder(), 1u);
}

TEST_F(OutputFile, AnInterruptedWriteLeavesNoTemporaryFile) {
  // In a child: install the handlers, start a write and be terminated in the middle of it.
  std::ofstream(path("result.json")) << "before";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    rbla::io::remove_temporary_files_on_signals();
    rbla::io::write_output(path("result.json"), [](std::ostream& out) {
      out << std::string(100000, 'x');
      out.flush();
      std::raise(SIGTERM);
    });
    ::_exit(0);  // not reached: SIGTERM ends the child
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "the signal still ends the program";
  EXPECT_EQ(read(path("result.json")), "before");
  EXPECT_EQ(files_in_folder(), 1u) << "a temporary file was left behind";
}
