// Writing output so a reader never sees half a file: write a temporary file next to the target,
// flush it, then rename it over the target (rename is atomic within one POSIX file system).
#pragma once

#include <string>

namespace rbla::io {

/// Writes `text` to `path` atomically ("-" writes to standard output). Throws std::runtime_error
/// with the path and the system's reason when it cannot; the target is then left untouched.
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace rbla::io
