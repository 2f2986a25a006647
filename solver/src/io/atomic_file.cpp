#include "io/atomic_file.hpp"

#include "io/file_error.hpp"

#include <array>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <streambuf>

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace rbla::io {

namespace {

// ---- The temporary file being written, for the signal handlers ---------------------------------

char g_temporary[PATH_MAX + 1];
volatile std::sig_atomic_t g_has_temporary = 0;

void remember_temporary(const std::string& path) {
  if (path.size() > PATH_MAX) return;
  std::memcpy(g_temporary, path.c_str(), path.size() + 1);
  g_has_temporary = 1;  // set after the copy: a signal in between finds nothing to remove
}

void forget_temporary() { g_has_temporary = 0; }

/// Creates the temporary file and remembers it with the signals that remove it blocked: a SIGTERM
/// between the two left it behind (a sweep task ended with its parent left a point's .tmp- file, in
/// one CI run of hundreds). A signal that arrives meanwhile is delivered when they are unblocked,
/// and its handler then removes the file.
int create_temporary(std::string& temporary) {
  sigset_t removing, before;
  sigemptyset(&removing);
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&removing, signal_number);
  pthread_sigmask(SIG_BLOCK, &removing, &before);
  const int fd = ::mkostemp(temporary.data(), O_CLOEXEC);
  const int error = errno;  // the caller reports mkostemp's
  if (fd >= 0) remember_temporary(temporary);
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
  errno = error;
  return fd;
}

extern "C" void remove_temporary_and_die(int signal_number) {
  if (g_has_temporary) ::unlink(g_temporary);  // async-signal-safe
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

// ---- Paths ---------------------------------------------------------------------------------------

std::string folder_of(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string name_of(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// An output path as messages name it ("-" is standard output here).
std::string shown(const std::string& path) { return path == "-" ? std::string("standard output") : quoted_path(path); }

[[noreturn]] void refuse(const OutputTarget& out, const std::string& why, int error = 0) {
  std::string message = "cannot write " + shown(out.path);
  if (!out.target.empty() && out.target != out.path) message += " (a link to " + quoted_path(out.target) + ")";
  message += ": " + why;
  if (error != 0) message += std::string(why.empty() ? "" : ": ") + std::strerror(error);
  throw FileError(out.path, message);
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "it is a directory";
  if (S_ISBLK(mode)) return "it is a block device; rbla writes to regular files, pipes, character devices or '-'";
  if (S_ISSOCK(mode)) return "it is a socket; rbla writes to regular files, pipes, character devices or '-'";
  return "it is not a file rbla can write";
}

/// Follows symbolic links from `out.path` to what is at the end: fills kind, target, identity.
void follow_links(OutputTarget& out) {
  // What the path leads to as the system follows it: a pipe or terminal behind /proc/self/fd/1,
  // /dev/stdout or a shell's >(command) is a link whose text ("pipe:[123]") names no file.
  struct stat end {};
  if (::stat(out.path.c_str(), &end) == 0 && !S_ISREG(end.st_mode)) {
    out.target = out.path;
    out.identity = FileIdentity{end.st_dev, end.st_ino};
    if (S_ISFIFO(end.st_mode) || S_ISCHR(end.st_mode)) out.kind = OutputKind::Stream;
    else refuse(out, kind_of(end.st_mode));
    return;
  }
  std::string current = out.path;
  for (int hops = 0;; ++hops) {
    out.target = current;
    struct stat info {};
    if (::lstat(current.c_str(), &info) != 0) {
      if (errno != ENOENT) refuse(out, "", errno);
      out.kind = OutputKind::Replace;  // nothing there yet
      return;
    }
    if (S_ISLNK(info.st_mode)) {
      if (hops >= 40) refuse(out, "", ELOOP);
      std::array<char, PATH_MAX> link{};
      const ssize_t n = ::readlink(current.c_str(), link.data(), link.size() - 1);
      if (n < 0) refuse(out, "cannot read the link", errno);
      const std::string to(link.data(), static_cast<std::size_t>(n));
      current = to.front() == '/' ? to : folder_of(current) + "/" + to;
      continue;
    }
    out.identity = FileIdentity{info.st_dev, info.st_ino};
    if (S_ISREG(info.st_mode)) out.kind = OutputKind::Replace;
    else if (S_ISFIFO(info.st_mode) || S_ISCHR(info.st_mode)) out.kind = OutputKind::Stream;
    else refuse(out, kind_of(info.st_mode));
    return;
  }
}

// ---- Writing to a file descriptor ----------------------------------------------------------------

/// An output buffer over a file descriptor that remembers the first error (errno) it met.
class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd), data_(1 << 16) { setp(data_.data(), data_.data() + data_.size()); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    const char* from = pbase();
    while (error_ == 0 && from < pptr()) {
      const ssize_t n = ::write(fd_, from, static_cast<std::size_t>(pptr() - from));
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) error_ = errno;
      else from += n;
    }
    setp(data_.data(), data_.data() + data_.size());
    return error_ == 0;
  }
  int fd_;
  int error_ = 0;
  std::vector<char> data_;
};

/// Runs `write` into `fd`; returns 0 or the errno of the first failed write.
int write_into(int fd, const std::function<void(std::ostream&)>& write) {
  FdBuffer buffer(fd);
  std::ostream out(&buffer);
  write(out);
  out.flush();
  return buffer.error() != 0 ? buffer.error() : (out ? 0 : EIO);
}

mode_t process_umask() {
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return mask;
}

void write_stream(const OutputTarget& out, const std::function<void(std::ostream&)>& write) {
  int fd = STDOUT_FILENO;
  if (out.kind == OutputKind::StandardOutput) {
    std::cout.flush();  // what the program printed before comes first
  } else {
    fd = ::open(out.target.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);  // a FIFO waits for its reader
    if (fd < 0) refuse(out, "", errno);
    struct stat info {};
    if (::fstat(fd, &info) != 0 || !(S_ISFIFO(info.st_mode) || S_ISCHR(info.st_mode))) {
      ::close(fd);
      refuse(out, "it changed while being opened");
    }
  }
  int error = 0;
  try {
    error = write_into(fd, write);
  } catch (...) {
    if (fd != STDOUT_FILENO) ::close(fd);
    throw;
  }
  if (fd != STDOUT_FILENO && ::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) refuse(out, "", error);
}

/// The mode, owner and group the new file takes: the old file's, or a new file's (0666 less the
/// umask) when there is none. Fails when what is there is no longer a regular file.
struct stat replaced_file(const OutputTarget& out) {
  struct stat info {};
  if (::lstat(out.target.c_str(), &info) == 0) {
    if (!S_ISREG(info.st_mode)) refuse(out, "it changed while being written: it is no longer a regular file");
    return info;
  }
  if (errno != ENOENT) refuse(out, "", errno);
  info.st_mode = S_IFREG | (0666 & ~process_umask());
  info.st_uid = ::geteuid();
  info.st_gid = ::getegid();
  return info;
}

void write_replace(const OutputTarget& out, const std::function<void(std::ostream&)>& write) {
  const std::string folder = folder_of(out.target);
  // The name is cut so that the temporary name fits NAME_MAX (255) with its suffix.
  std::string temporary = folder + "/" + out.name.substr(0, 200) + ".tmp-XXXXXX";
  const int fd = create_temporary(temporary);
  if (fd < 0) refuse(out, "cannot create a temporary file in " + quoted_path(folder), errno);
  auto fail = [&](const std::string& why, int error) {
    ::close(fd);
    ::unlink(temporary.c_str());
    forget_temporary();
    refuse(out, why, error);
  };
  int error = 0;
  try {
    error = write_into(fd, write);
  } catch (...) {
    ::close(fd);
    ::unlink(temporary.c_str());
    forget_temporary();
    throw;
  }
  if (error != 0) fail("", error);
  if (::fsync(fd) != 0) fail("cannot flush it to disk", errno);
  const struct stat old = replaced_file(out);
  if (::fchmod(fd, old.st_mode & 07777) != 0) fail("cannot set its permissions", errno);
  // Owner and group as before where we may (root, or a group we belong to); else they become ours.
  if (old.st_uid != ::geteuid() || old.st_gid != ::getegid()) {
    if (::fchown(fd, old.st_uid, old.st_gid) != 0) (void)::fchown(fd, static_cast<uid_t>(-1), old.st_gid);
  }
  if (::close(fd) != 0) {
    error = errno;
    ::unlink(temporary.c_str());
    forget_temporary();
    refuse(out, "", error);
  }
  replaced_file(out);  // still a regular file or nothing, just before it is replaced
  if (::rename(temporary.c_str(), out.target.c_str()) != 0) {
    error = errno;
    ::unlink(temporary.c_str());
    forget_temporary();
    refuse(out, "cannot move the new file into place", error);
  }
  forget_temporary();
  // The rename itself is durable once the folder is flushed; the file is in place either way.
  const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    (void)::fsync(dir);
    ::close(dir);
  }
}

}  // namespace

OutputTarget resolve_output(const std::string& path) {
  OutputTarget out;
  out.path = path;
  if (path == "-") {
    out.kind = OutputKind::StandardOutput;
    return out;
  }
  if (path.empty()) throw FileError(path, "cannot write to an empty path");
  follow_links(out);
  if (out.kind != OutputKind::Replace) return out;
  out.name = name_of(out.target);
  if (out.name.empty() || out.name == "." || out.name == "..") refuse(out, "it names a folder, not a file");
  const std::string folder = folder_of(out.target);
  struct stat info {};
  if (::stat(folder.c_str(), &info) != 0) {
    refuse(out, errno == ENOENT ? "its folder " + quoted_path(folder) + " does not exist" : "", errno == ENOENT ? 0 : errno);
  }
  if (!S_ISDIR(info.st_mode)) refuse(out, quoted_path(folder) + " is not a folder");
  out.directory = FileIdentity{info.st_dev, info.st_ino};
  // Asked before any work: the new file is made in the folder and renamed over the old one, which
  // the folder's permission alone would allow; a file we may not write (read-only, or another
  // user's) is not ours to replace, as it would not be for cp or a shell's redirection.
  if (::access(folder.c_str(), W_OK | X_OK) != 0) refuse(out, "cannot write into its folder " + quoted_path(folder), errno);
  if (out.identity && ::access(out.target.c_str(), W_OK) != 0) refuse(out, "the file there may not be written", errno);
  return out;
}

std::vector<OutputTarget> resolve_outputs_in_folder(const std::string& folder, const std::vector<std::string>& names) {
  struct stat info {};
  if (::stat(folder.c_str(), &info) != 0) {
    if (errno == ENOENT) return {};
    throw FileError(folder, "cannot write into " + quoted_path(folder) + ": " + std::strerror(errno));
  }
  if (!S_ISDIR(info.st_mode)) throw FileError(folder, "cannot write into " + quoted_path(folder) + ": it is not a folder");
  std::vector<OutputTarget> targets;
  for (const std::string& name : names) targets.push_back(resolve_output((std::filesystem::path(folder) / name).string()));
  return targets;
}

void make_folder(const std::string& folder) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw FileError(folder, "cannot create the folder " + quoted_path(folder) + ": " + error.message());
}

bool goes_to_standard_output(const OutputTarget& out) {
  if (out.kind == OutputKind::StandardOutput) return true;
  struct stat info {};
  return out.identity && ::fstat(STDOUT_FILENO, &info) == 0 && *out.identity == FileIdentity{info.st_dev, info.st_ino};
}

void write_output(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const OutputTarget out = resolve_output(path);
  if (out.kind == OutputKind::Replace) write_replace(out, write);
  else write_stream(out, write);
}

void write_file_atomically(const std::string& path, const std::string& text) {
  write_output(path, [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

void check_outputs(const std::string& input, const std::vector<OutputTarget>& outputs) {
  const std::optional<FileIdentity> read = identity_of(input);
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const OutputTarget& a = outputs[i];
    if (read && a.identity && *a.identity == *read) {
      throw FileError(a.path, "will not write " + shown(a.path) + ": it is the model being read (" +
                                  quoted_path(input) + ")");
    }
    for (std::size_t j = 0; j < i; ++j) {
      const OutputTarget& b = outputs[j];
      const bool both_stdout = a.kind == OutputKind::StandardOutput && b.kind == OutputKind::StandardOutput;
      const bool same_file = a.kind == OutputKind::Replace && b.kind == OutputKind::Replace &&
                             ((a.identity && b.identity && *a.identity == *b.identity) ||
                              (!a.identity && !b.identity && a.directory == b.directory && a.name == b.name));
      if (both_stdout || same_file) {
        throw FileError(a.path, "will not write " + shown(a.path) + " and " + shown(b.path) +
                                    ": they are the same " + (both_stdout ? "stream" : "file") +
                                    ", and one output would overwrite the other");
      }
    }
  }
}

void remove_temporary_files_on_signals() {
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal_number, remove_temporary_and_die);
}

}  // namespace rbla::io
