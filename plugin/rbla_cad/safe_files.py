"""Reading inputs and writing outputs by the solver's rules (solver/src/io/atomic_file.hpp), for
the plugin's command-line writers (compas_import, ...).

    from rbla_cad.safe_files import FileError, read_input, resolve_output, check_not_input, write_output
    data = read_input("in.json")                 # bytes; refuses devices, folders, huge files
    out = resolve_output("out.json")             # before the work: refuses what cannot be written
    check_not_input(out, ["in.json"])            # an output that is an input is refused
    write_output(out, text)

What an output path leads to decides how it is written:

* ``"-"``: standard output;
* a FIFO or a character device (a pipe someone reads, a terminal, /dev/null, /dev/full): written
  into as a stream, never replaced;
* a regular file, or nothing yet: written to a temporary file in the same folder, flushed, then
  renamed over it (atomic on one file system), keeping the old file's permission bits (and owner
  and group where the system allows: as root, or a group we belong to);
* a symbolic link: followed, its target written by the rules above (a dangling link gets its
  target created);
* a directory, a block device or a socket: refused; so is a file we may not write, or a folder we
  may not write into (rename alone would let us replace a read-only file).

On any failure the temporary file is removed and what was at the path is left as it was, also
when SIGINT, SIGTERM or SIGHUP ends the process mid-write (the signal then does what it would have
done: the handler is only there while a temporary file exists, and only over default handlers).
Every refusal is a :class:`FileError` whose message is one line naming the path.
"""

import collections
import contextlib
import errno
import os
import signal
import stat
import sys
import tempfile
import threading

# The solver's --max-input-bytes default (solver/src/io/input_limits.hpp).
MAX_INPUT_BYTES = 256 << 20

STDOUT, STREAM, REPLACE = "stdout", "stream", "replace"

# path: as given; kind: STDOUT, STREAM or REPLACE; target: the file written (links followed);
# identity: (st_dev, st_ino) of what is there now, or None.
OutputTarget = collections.namedtuple("OutputTarget", "path kind target identity")


class FileError(OSError):
    """A file that cannot be read or written; the message names it. An OSError, so that code
    catching what open() and os.replace() raise (ModelBuilder.write's callers) catches it too."""

    def __init__(self, path, message):
        OSError.__init__(self, message)  # one argument: str() is the message, no "[Errno ...]"
        self.path = path


def _shown(path):
    return "standard output" if path == "-" else "'%s'" % path


def _kind_of(mode):
    if stat.S_ISDIR(mode):
        return "it is a directory"
    if stat.S_ISBLK(mode):
        return "it is a block device"
    if stat.S_ISSOCK(mode):
        return "it is a socket"
    if stat.S_ISCHR(mode):
        return "it is a character device"
    return "it is not a regular file"


def _identity(st):
    return (st.st_dev, st.st_ino)


# --------------------------------------------------------------------------------------------
# Inputs
# --------------------------------------------------------------------------------------------

def _read_capped(fh, path, max_bytes):
    """Everything fh gives, refused as soon as it passes max_bytes (a pipe has no size)."""
    chunks, total = [], 0
    while True:
        chunk = fh.read(1 << 20)
        if not chunk:
            return b"".join(chunks)
        total += len(chunk)
        if total > max_bytes:
            shown = "standard input" if path == "-" else "'%s'" % path
            raise FileError(path, "cannot read %s: more than %d bytes (the input limit)"
                            % (shown, max_bytes))
        chunks.append(chunk)


def read_input(path, max_bytes=MAX_INPUT_BYTES):
    """The bytes of a regular file or FIFO ("-": standard input). Devices, folders and sockets are
    refused before reading (/dev/zero would never end), and so is anything above max_bytes."""
    if path == "-":
        stream = getattr(sys.stdin, "buffer", None)
        if stream is None:
            raise FileError(path, "cannot read standard input: it is not a byte stream")
        return _read_capped(stream, path, max_bytes)
    try:
        st = os.stat(path)
    except OSError as e:
        raise FileError(path, "cannot read '%s': %s" % (path, e.strerror))
    if not (stat.S_ISREG(st.st_mode) or stat.S_ISFIFO(st.st_mode)):
        raise FileError(path, "cannot read '%s': %s; give a JSON file, a pipe or '-'"
                        % (path, _kind_of(st.st_mode)))
    if st.st_size > max_bytes:
        raise FileError(path, "cannot read '%s': it is %d bytes, more than the input limit of %d"
                        % (path, st.st_size, max_bytes))
    try:
        with open(path, "rb") as fh:
            return _read_capped(fh, path, max_bytes)
    except FileError:
        raise
    except OSError as e:
        raise FileError(path, "cannot read '%s': %s" % (path, e.strerror))


def input_identity(path):
    """(st_dev, st_ino) of an input, however it is spelled ("-": standard input when it is a
    file), or None."""
    try:
        st = os.fstat(0) if path == "-" else os.stat(path)
    except OSError:
        return None
    if path == "-" and not stat.S_ISREG(st.st_mode):
        return None
    return _identity(st)


# --------------------------------------------------------------------------------------------
# Outputs
# --------------------------------------------------------------------------------------------

def _refuse(path, target, why):
    link = " (a link to '%s')" % target if target and target != path else ""
    raise FileError(path, "cannot write %s%s: %s" % (_shown(path), link, why))


def _follow_links(path):
    """The path a chain of symbolic links ends at, whether or not a file is there."""
    current = path
    for _ in range(40):
        try:
            if not stat.S_ISLNK(os.lstat(current).st_mode):
                return current
        except FileNotFoundError:
            return current
        except OSError as e:
            _refuse(path, current, e.strerror)
        to = os.readlink(current)
        current = to if os.path.isabs(to) else os.path.join(os.path.dirname(current), to)
    _refuse(path, current, os.strerror(errno.ELOOP))


def resolve_output(path):
    """Where an output path leads (an OutputTarget), found before anything is written so a run
    can refuse it before doing the work. Raises FileError when it cannot be written."""
    if path == "-":
        return OutputTarget(path, STDOUT, None, None)
    if not path:
        raise FileError(path, "cannot write to an empty path")
    # What the system reaches through the path: a pipe behind /dev/stdout or /proc/self/fd/1 is a
    # link whose text ("pipe:[123]") names no file, so devices and pipes are judged from here.
    try:
        st = os.stat(path)
    except OSError:
        st = None
    if st is not None and not stat.S_ISREG(st.st_mode):
        if stat.S_ISFIFO(st.st_mode) or stat.S_ISCHR(st.st_mode):
            return OutputTarget(path, STREAM, path, _identity(st))
        _refuse(path, None, _kind_of(st.st_mode))
    target = _follow_links(path)
    name = os.path.basename(target)
    if name in ("", ".", ".."):
        _refuse(path, target, "it names a folder, not a file")
    folder = os.path.dirname(target) or "."
    if not os.path.isdir(folder):
        _refuse(path, target, "its folder '%s' does not exist or is not a folder" % folder)
    # The new file is made in the folder and renamed over the old one, which the folder's
    # permission alone would allow; a file we may not write is not ours to replace.
    if not os.access(folder, os.W_OK | os.X_OK):
        _refuse(path, target, "cannot write into its folder '%s'" % folder)
    if st is not None and not os.access(target, os.W_OK):
        _refuse(path, target, "the file there may not be written")
    return OutputTarget(path, REPLACE, target, _identity(st) if st is not None else None)


def check_not_input(out, inputs):
    """Refuses an output that is one of the inputs (the same file through any spelling, link or
    hard link: compared by device and inode)."""
    if out.identity is None:
        return
    for path in inputs:
        if input_identity(path) == out.identity:
            raise FileError(out.path, "will not write %s: it is the input '%s'" % (_shown(out.path), path))


def _write_all(fd, data):
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _write_stream(out, data):
    try:
        fd = os.open(out.target, os.O_WRONLY | getattr(os, "O_NOCTTY", 0))  # a FIFO waits for its reader
    except OSError as e:
        _refuse(out.path, None, e.strerror)
    try:
        # it may have been swapped for a file since resolve_output: never write a file this way
        mode = os.fstat(fd).st_mode
        if not (stat.S_ISFIFO(mode) or stat.S_ISCHR(mode)):
            _refuse(out.path, None, "it changed while being opened")
        _write_all(fd, data)
    except FileError:
        raise
    except OSError as e:
        _refuse(out.path, None, e.strerror)
    finally:
        os.close(fd)


# --------------------------------------------------------------------------------------------
# Temporary files removed on signals (the solver's remove_temporary_files_on_signals)
# --------------------------------------------------------------------------------------------

# Temporary files being written now: a signal that ends the process removes them first.
_temporaries = set()
_SIGNALS = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, n))
_previous_handlers = {}


def _remove_temporaries_then_resignal(signum, frame):
    for path in list(_temporaries):
        _remove(path)
    _temporaries.clear()
    previous = _previous_handlers.get(signum, signal.SIG_DFL)
    if callable(previous):  # Python's own SIGINT handler: KeyboardInterrupt, as without us
        previous(signum, frame)
        return
    signal.signal(signum, signal.SIG_DFL)  # ended by the signal, as without us
    signal.raise_signal(signum)


def _install_signal_handlers():
    """Our handler over the default ones ({signal: previous} of those replaced). Not over a
    handler someone else set (or SIG_IGN, under nohup), and not outside the main thread, where
    Python does not allow it: the temporary file is then left to the usual error handling."""
    installed = {}
    if threading.current_thread() is not threading.main_thread():
        return installed
    for signum in _SIGNALS:
        previous = signal.getsignal(signum)
        if previous in (signal.SIG_DFL, signal.default_int_handler):
            try:
                signal.signal(signum, _remove_temporaries_then_resignal)
            except (ValueError, OSError):
                continue
            _previous_handlers[signum] = installed[signum] = previous
    return installed


@contextlib.contextmanager
def _removed_on_signals(path):
    """While this lasts, SIGINT, SIGTERM or SIGHUP ending the process removes path first. The
    handlers are there only meanwhile: a Python handler runs only when Python code runs, so left
    in place it could keep an idle host (Rhino) from ending on SIGTERM. Python runs a pending
    handler before it changes one, so putting the old ones back loses no signal."""
    installed = _install_signal_handlers()
    _temporaries.add(path)
    try:
        yield
    finally:
        _temporaries.discard(path)
        for signum, previous in installed.items():
            signal.signal(signum, previous)


def _keep_owner(fd, old):
    """Owner and group of the replaced file where we may (root; or the group alone, when we
    belong to it); else the new file is ours, as any new file would be. As the solver does."""
    if not hasattr(os, "fchown") or (old.st_uid, old.st_gid) == (os.geteuid(), os.getegid()):
        return
    try:
        os.fchown(fd, old.st_uid, old.st_gid)
    except OSError:
        try:
            os.fchown(fd, -1, old.st_gid)
        except OSError:
            pass


def _write_replace(out, data):
    folder = os.path.dirname(out.target) or "."
    name = os.path.basename(out.target)
    try:
        # name cut so the temporary name stays within NAME_MAX with its suffix
        fd, tmp = tempfile.mkstemp(prefix=name[:200] + ".tmp-", dir=folder)
    except OSError as e:
        _refuse(out.path, out.target, "cannot create a temporary file in '%s': %s" % (folder, e.strerror))
    with _removed_on_signals(tmp):
        try:
            try:
                _write_all(fd, data)
                os.fsync(fd)
                try:
                    old = os.stat(out.target)
                    if not stat.S_ISREG(old.st_mode):
                        _refuse(out.path, out.target, "it changed while being written: it is no longer a regular file")
                    _keep_owner(fd, old)  # first: a change of owner may clear set-id bits
                    mode = stat.S_IMODE(old.st_mode)
                except FileNotFoundError:
                    mode = 0o666 & ~_umask()  # a new file gets what open() would give it
                if hasattr(os, "fchmod"):
                    os.fchmod(fd, mode)
                else:  # Windows
                    os.chmod(tmp, mode)
            finally:
                os.close(fd)
            os.replace(tmp, out.target)
        except BaseException as e:  # FileError, KeyboardInterrupt...: no temporary file left behind
            _remove(tmp)
            if isinstance(e, OSError) and not isinstance(e, FileError):
                _refuse(out.path, out.target, e.strerror or str(e))
            raise


def _remove(path):
    try:
        os.unlink(path)
    except OSError:
        pass


def write_output(out, data):
    """Writes data (str as UTF-8, or bytes) to out (an OutputTarget, or a path resolved here) by
    the rules of the module. Raises FileError naming the path."""
    if not isinstance(out, OutputTarget):
        out = resolve_output(out)
    if isinstance(data, str):
        data = data.encode("utf-8")
    if out.kind == STDOUT:
        sys.stdout.flush()  # what was printed before comes first
        stream = getattr(sys.stdout, "buffer", None)
        try:
            if stream is not None:
                stream.write(data)
            else:
                sys.stdout.write(data.decode("utf-8"))
            sys.stdout.flush()
        except OSError as e:
            _refuse(out.path, None, e.strerror or str(e))
    elif out.kind == STREAM:
        _write_stream(out, data)
    else:
        _write_replace(out, data)
