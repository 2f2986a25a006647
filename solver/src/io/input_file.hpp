// Opening the model for reading: a regular file, a FIFO (a pipe, as `<(command)` gives) or
// standard input ("-"), read through a buffer that refuses more than a set number of bytes, so
// an endless stream or an enormous file ends in a message, not in exhausted memory.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <istream>
#include <memory>
#include <optional>
#include <string>

namespace rbla::io {

/// A file on this machine (device and inode): two paths name one file exactly when their
/// identities are equal, however they are spelled and through whatever links.
struct FileIdentity {
  dev_t device = 0;
  ino_t inode = 0;
  bool operator==(const FileIdentity& other) const { return device == other.device && inode == other.inode; }
};

/// The identity of what `path` names, links followed ("-": standard input when it is a regular
/// file); empty when nothing is there or it cannot be examined.
std::optional<FileIdentity> identity_of(const std::string& path);

/// How a path is named in messages: quoted and escaped, or "standard input" for "-".
std::string quoted_path(const std::string& path);

/// The model as a stream of bytes. Throws io::FileError (naming the path and the system's reason)
/// when the path cannot be opened or is a directory, a device or a socket, and model::ModelError
/// when the input is longer than `max_bytes` (checked from the file's size before reading, and
/// while reading for pipes and standard input).
class InputFile {
 public:
  InputFile(const std::string& path, std::uint64_t max_bytes);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  std::istream& stream();

 private:
  class Buffer;
  std::unique_ptr<Buffer> buffer_;
  std::unique_ptr<std::istream> stream_;
};

}  // namespace rbla::io
