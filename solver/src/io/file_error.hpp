// A file that cannot be read or written: what was wrong with the file system, not with the
// model's content. The program reports it with its own exit code (README, "exit code").
#pragma once

#include <stdexcept>
#include <string>

namespace rbla::io {

class FileError : public std::runtime_error {
 public:
  /// `message` names the path itself (quoted through io::printable).
  FileError(std::string path, const std::string& message) : std::runtime_error(message), path_(std::move(path)) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace rbla::io
