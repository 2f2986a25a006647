// Writing output so that a reader never sees half a file and nothing that was not ours is
// replaced. What a path leads to decides how it is written:
//   - "-": standard output, streamed;
//   - a FIFO or a character device (a pipe someone reads, a terminal, a null device): streamed
//     into it, never replaced;
//   - a regular file, or nothing yet: written to a temporary file beside it, flushed to disk, then
//     renamed over it (rename is atomic within one POSIX file system), keeping the old file's
//     permission bits (and its owner and group where the system lets us);
//   - a symbolic link: followed, and its target written by the rules above (a dangling link
//     gets its target created);
//   - a directory, a block device or a socket: refused; so is a regular file we may not write, or
//     a folder we may not write into (access(2)), though rename would replace such a file.
// On any failure the temporary file is removed and whatever was at the path is left as it was.
#pragma once

#include "io/input_file.hpp"

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace rbla::io {

enum class OutputKind { StandardOutput, Stream, Replace };

/// Where an output path leads, found before anything is written (so a run can refuse it before
/// spending time on an analysis).
struct OutputTarget {
  std::string path;                       ///< as given
  OutputKind kind = OutputKind::Replace;
  std::string target;                     ///< the file written: `path` with symbolic links followed
  std::optional<FileIdentity> identity;   ///< the file there now (Replace over a file, Stream)
  std::optional<FileIdentity> directory;  ///< Replace: the folder the target is (to be) in
  std::string name;                       ///< Replace: the target's name in that folder
};

/// Examines `path`. Throws io::FileError naming the path when it cannot be written by the rules
/// above (a directory, a device that is not a character device, a missing folder, a loop of
/// links, no permission to look).
OutputTarget resolve_output(const std::string& path);

/// The targets of files `names` inside `folder` (resolve_output of each) when the folder exists;
/// none when it does not yet. Throws io::FileError when `folder` is there but is not a folder.
std::vector<OutputTarget> resolve_outputs_in_folder(const std::string& folder, const std::vector<std::string>& names);

/// Creates `folder` and its missing parents. Throws io::FileError naming it when it cannot.
void make_folder(const std::string& folder);

/// True when `out` is standard output: "-", or the file, pipe or terminal that standard output
/// is (/proc/self/fd/1, /dev/stdout, or a path naming the file it was redirected to).
bool goes_to_standard_output(const OutputTarget& out);

/// Writes what `write` puts into the stream to `path` by the rules above. Throws io::FileError
/// naming the path on failure (and passes on what `write` throws), after removing the temporary
/// file; the target is then untouched (a stream may have received part of the output).
void write_output(const std::string& path, const std::function<void(std::ostream&)>& write);
/// Writes `text` to `path` (as write_output).
void write_file_atomically(const std::string& path, const std::string& text);

/// Refuses (io::FileError naming the output) an output that is the input `input` ("-": standard
/// input when it is a regular file) however either is spelled, through links of any kind, and two
/// outputs that are the same file or both standard output. Outputs to a FIFO or a character
/// device may be shared.
void check_outputs(const std::string& input, const std::vector<OutputTarget>& outputs);

/// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove the temporary file being written
/// (if any) before the signal ends the program as it would have.
void remove_temporary_files_on_signals();

}  // namespace rbla::io
