#include "io/input_file.hpp"

#include "io/file_error.hpp"
#include "io/input_limits.hpp"
#include "io/printable.hpp"
#include "model/errors.hpp"

#include <cerrno>
#include <cstring>
#include <streambuf>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace rbla::io {

namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void fail(const std::string& path, const std::string& what, int error) {
  throw FileError(path, "cannot read " + quoted_path(path) + ": " + what + (error ? std::string(": ") + std::strerror(error) : ""));
}

std::string too_large(const std::string& path, std::uint64_t max_bytes) {
  return quoted_path(path) + " is larger than " + limit_text(&InputLimits::max_bytes, max_bytes);
}

}  // namespace

std::string quoted_path(const std::string& path) {
  return path == "-" ? std::string("standard input") : "'" + printable(path, 1000) + "'";
}

std::optional<FileIdentity> identity_of(const std::string& path) {
  struct stat info {};
  if (path == "-") {
    if (::fstat(STDIN_FILENO, &info) != 0 || !S_ISREG(info.st_mode)) return std::nullopt;
  } else if (::stat(path.c_str(), &info) != 0) {
    return std::nullopt;
  }
  return FileIdentity{info.st_dev, info.st_ino};
}

/// Reads a file descriptor in 64 KiB pieces and throws once more than max_bytes have come.
class InputFile::Buffer : public std::streambuf {
 public:
  Buffer(std::string path, int fd, bool owned, std::uint64_t max_bytes)
      : path_(std::move(path)), fd_(fd), owned_(owned), max_bytes_(max_bytes), data_(1 << 16) {}
  ~Buffer() override {
    if (owned_) ::close(fd_);
  }

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    ssize_t n = 0;
    do {
      n = ::read(fd_, data_.data(), data_.size());
    } while (n < 0 && errno == EINTR);
    if (n < 0) fail(path_, "read error", errno);
    if (n == 0) return traits_type::eof();
    if (const void* nul = std::memchr(data_.data(), '\0', static_cast<std::size_t>(n))) {
      throw model::ModelError("", nul_byte_text(quoted_path(path_), read_ + static_cast<std::uint64_t>(static_cast<const char*>(nul) - data_.data())));
    }
    read_ += static_cast<std::uint64_t>(n);
    if (read_ > max_bytes_) throw model::ModelError("", too_large(path_, max_bytes_));
    setg(data_.data(), data_.data(), data_.data() + n);
    return traits_type::to_int_type(*gptr());
  }

 private:
  std::string path_;
  int fd_;
  bool owned_;
  std::uint64_t max_bytes_;
  std::uint64_t read_ = 0;
  std::vector<char> data_;
};

InputFile::InputFile(const std::string& path, std::uint64_t max_bytes) {
  if (path == "-") {
    buffer_ = std::make_unique<Buffer>(path, STDIN_FILENO, false, max_bytes);
  } else {
    // Examine before opening: opening a device can block or act on it (a tape rewinds, a serial
    // line waits for a carrier); a FIFO is opened blocking, as a shell would, to wait for its writer.
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) fail(path, "cannot open it", errno);
    if (!S_ISREG(info.st_mode) && !S_ISFIFO(info.st_mode)) {
      fail(path, std::string("it is ") + kind_of(info.st_mode) + "; a model is a regular file, a pipe or '-'", 0);
    }
    if (S_ISREG(info.st_mode) && static_cast<std::uint64_t>(info.st_size) > max_bytes) {
      throw model::ModelError("", too_large(path, max_bytes) + ": it is " + std::to_string(info.st_size) + " bytes");
    }
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | (S_ISREG(info.st_mode) ? O_NONBLOCK : 0));
    if (fd < 0) fail(path, "cannot open it", errno);
    // What was opened must still be what was examined (it may have been replaced in between).
    struct stat opened {};
    if (::fstat(fd, &opened) != 0 || opened.st_dev != info.st_dev || opened.st_ino != info.st_ino) {
      ::close(fd);
      fail(path, "it changed while being opened", 0);
    }
    buffer_ = std::make_unique<Buffer>(path, fd, true, max_bytes);
  }
  stream_ = std::make_unique<std::istream>(buffer_.get());
}

InputFile::~InputFile() = default;

std::istream& InputFile::stream() { return *stream_; }

}  // namespace rbla::io
