"""Run the rbla solver as a subprocess, with progress, timeout and cancel.

    from rbla_cad.runner import Runner
    runner = Runner()                       # executable: argument, $RBLA_EXE, or rbla on PATH
    outcome = runner.solve(model_dict, progress=print_event, cancel=stop_event, timeout=60)
    outcome.result.load_multiplier

The model (a dict, a ModelBuilder, or the path of a model JSON file) is written to a temporary
folder, ``rbla solve MODEL -o RESULT -v`` runs there, and the result JSON is read back as a
:class:`rbla_cad.result.Result`.

Progress. Standard error is read line by line while the solver runs. ``progress(event)`` gets a
:class:`ProgressEvent` with ``kind``:

* ``"stage"``     - a solver progress line (``rbla: reading ...``, ``rbla: model: ...``,
  ``rbla: analysis: ...``, ``rbla: solved in ...``, ``rbla: wrote ...``), text without prefix;
* ``"warning"``   - ``rbla: warning [code]...``; ``data`` = {"code": ...};
* ``"iteration"`` - an interior-point iteration row of the ``-v`` table; ``data`` = dict with
  iteration, primal_objective, dual_objective, relative_gap, primal_residual, dual_residual,
  mu, tau, kappa, step (the columns the table has);
* ``"log"``       - any other line (table headers, solver summary).

Callbacks (``progress`` and a callable ``cancel``) always run on the calling thread: the output
is read by helper threads and dispatched from the polling loop, so a CAD host may touch its UI
from them.

Outcomes. Exit 0 returns a :class:`RunOutcome` (verdicts collapse / no_mechanism /
cannot_stand are answers). Exit 1 raises :class:`UsageError`, 2 :class:`InvalidModelError`
(``issues``: list of (JSON pointer, message) parsed from the solver's report), 3
:class:`SolverFailureError` (``result`` holds the result JSON the solver still wrote, with
status time_limit, iteration_limit, solver_failure ...), 4 :class:`OutputError`. A timeout
raises :class:`SolverTimeoutError`, a cancel :class:`CancelledError`; in both cases the
process is terminated (then killed after a grace period). Every exception carries the solver's
stderr text (``stderr``) and exit code (``exit_code``).
"""

import collections
import json
import os
import re
import shutil
import stat
import subprocess
import sys
import tempfile
import threading
import time

try:
    import queue
except ImportError:  # pragma: no cover
    import Queue as queue  # noqa: N813

from .result import Result

ENV_VAR = "RBLA_EXE"

ProgressEvent = collections.namedtuple("ProgressEvent", "kind text data")

_ITER_COLUMNS = ("iteration", "primal_objective", "dual_objective", "relative_gap",
                 "primal_residual", "dual_residual", "mu", "tau", "kappa", "step", "sigma",
                 "refinements")
_NUM = r"[+-]?(?:\d+\.?\d*(?:[eE][+-]?\d+)?|inf|nan)"
_ITER_RE = re.compile(r"^\s*(\d+)((?:\s+" + _NUM + r")+)\s*$")
_ISSUE_RE = re.compile(r"^\s+(\(document\)|/\S*):\s(.*)$")


class RblaError(Exception):
    """Base of the runner's errors; ``exit_code`` and ``stderr`` as far as known."""

    def __init__(self, message, exit_code=None, stderr="", result=None):
        Exception.__init__(self, message)
        self.exit_code = exit_code
        self.stderr = stderr
        self.result = result


class SolverNotFoundError(RblaError):
    """No rbla executable: pass one, set $RBLA_EXE, or put rbla on PATH."""


class UsageError(RblaError):
    """Exit 1: the command line was wrong (a bug of the caller or an incompatible rbla)."""


class InvalidModelError(RblaError):
    """Exit 2: the solver rejected the model. ``issues`` = [(pointer, message), ...]."""

    def __init__(self, message, exit_code=2, stderr="", issues=None):
        RblaError.__init__(self, message, exit_code, stderr)
        self.issues = list(issues or [])


class SolverFailureError(RblaError):
    """Exit 3: no answer (numerical failure, time or iteration limit). ``result`` holds the
    result the solver wrote (status explains), or None."""


class OutputError(RblaError):
    """Exit 4: the solver could not read or write a file (its message names the path)."""


class SolverTimeoutError(RblaError):
    """The run took longer than the timeout and was stopped."""


class CancelledError(RblaError):
    """The run was cancelled and stopped."""


RunOutcome = collections.namedtuple(
    "RunOutcome", "result exit_code verdict_line stderr model_path result_path svg_dir seconds")


def find_executable(executable=None):
    """The rbla executable: ``executable`` if given, else $RBLA_EXE, else ``rbla`` on PATH."""
    for candidate, origin in ((executable, "argument"), (os.environ.get(ENV_VAR), ENV_VAR)):
        if candidate:
            path = os.path.expanduser(candidate)
            if os.path.isfile(path) and os.access(path, os.X_OK):
                return os.path.abspath(path)
            found = shutil.which(path)
            if found:
                return found
            raise SolverNotFoundError("rbla executable %r (from %s) not found or not executable"
                                      % (candidate, origin))
    for name in ("rbla", "rbla.exe"):
        found = shutil.which(name)
        if found:
            return found
    raise SolverNotFoundError("rbla executable not found: pass its path, set %s, or put rbla "
                              "on PATH" % ENV_VAR)


def parse_stderr_line(line):
    """Classify one stderr line into a ProgressEvent."""
    text = line.rstrip("\r\n")
    if text.startswith("rbla: warning"):
        m = re.match(r"rbla: warning \[([^\]]*)\]", text)
        return ProgressEvent("warning", text[len("rbla: "):], {"code": m.group(1) if m else ""})
    if text.startswith("rbla: "):
        return ProgressEvent("stage", text[len("rbla: "):], None)
    m = _ITER_RE.match(text)
    if m:
        values = [m.group(1)] + m.group(2).split()
        data = {}
        for name, val in zip(_ITER_COLUMNS, values):
            data[name] = int(val) if name in ("iteration", "refinements") else float(val)
        return ProgressEvent("iteration", text, data)
    return ProgressEvent("log", text, None)


def parse_invalid_report(stderr):
    """[(pointer, message)] from the solver's 'rbla: invalid input:' block."""
    issues = []
    inside = False
    for line in stderr.splitlines():
        if line.startswith("rbla: invalid input"):
            inside = True
            continue
        if inside:
            m = _ISSUE_RE.match(line)
            if m:
                ptr = "" if m.group(1) == "(document)" else m.group(1)
                issues.append((ptr, m.group(2)))
            elif line.startswith("rbla: "):
                inside = False
    return issues


def _model_to_file(model, folder):
    """Write the model (dict / ModelBuilder / path) into folder; return the path."""
    if isinstance(model, str):
        if not os.path.isfile(model):
            raise RblaError("model file %r does not exist" % model)
        return os.path.abspath(model)
    if hasattr(model, "to_dict"):
        model = model.to_dict()
    path = os.path.join(folder, "model.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(model, f)
    return path


class Runner(object):
    """Runs ``rbla`` commands. executable: path or name (default $RBLA_EXE, then PATH);
    timeout: default seconds per run (None: no limit); poll: polling interval in seconds;
    grace: seconds between terminate and kill."""

    def __init__(self, executable=None, timeout=None, poll=0.05, grace=2.0):
        self.executable = find_executable(executable)
        self.timeout = timeout
        self.poll = poll
        self.grace = grace

    def version(self):
        out = subprocess.run([self.executable, "--version"], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, universal_newlines=True, timeout=30,
                             **_popen_extra())
        return out.stdout.strip()

    # ------------------------------------------------------------------------------------
    def solve(self, model, result_path=None, svg_dir=None, progress=None, cancel=None,
              timeout=None, verbose=True, workdir=None, keep_files=False, detail=None):
        """Solve a model; return a RunOutcome with the parsed Result (see module docs).

        result_path: where the result JSON goes (default: a temporary folder, removed after
        reading unless keep_files). svg_dir: also write the SVG pictures there. verbose: ask
        for the interior-point table (iteration events). cancel: a threading.Event or a
        callable returning True to stop. detail: "points" (the solver's default), "interfaces"
        (no contact points) or "blocks" (no interfaces section): how much of the mechanism the
        result holds (``rbla solve --detail``; contact points are most of a large model's result).
        """
        return self._analysis("solve", [], model, result_path, svg_dir, progress, cancel,
                              timeout, verbose, workdir, keep_files, detail)

    def worst_direction(self, model, tolerance=None, max_directions=None, **kwargs):
        """``rbla worst-direction``: the horizontal seismic direction the structure carries
        least. The outcome's result is the analysis along it; ``result.data["worst_direction"]``
        holds the search (alpha_min, angle, certified lower bound, every direction tried).
        Other keyword arguments as for solve()."""
        extra = []
        if tolerance is not None:
            extra += ["--tolerance", repr(float(tolerance))]
        if max_directions is not None:
            extra += ["--max-directions", str(int(max_directions))]
        return self._analysis("worst-direction", extra, model, **_analysis_kwargs(kwargs))

    def worst_settlement(self, model, cone_angle=None, tolerance=None, max_directions=None,
                         candidate_groups=None, **kwargs):
        """``rbla worst-settlement``: the settlement direction of the moving supports, within
        ``cone_angle`` degrees of gravity (default 30), that leaves the largest fraction R/R0
        of the initial reaction at collapse. The outcome's result is the settlement analysis
        along it; ``result.data["worst_settlement"]`` holds the search (ratio, tilt, azimuth,
        certified upper bound, every direction tried). ``candidate_groups``: groups of supports
        (each a list of block ids or labels, or one comma-separated string) of which only one
        settles at a time; each is searched and they are ranked, the most harmful group's
        analysis returned, the ranking in ``worst_settlement["candidate_groups"]``. Other
        keyword arguments as for solve()."""
        extra = []
        for group in candidate_groups or []:
            names = group.split(",") if isinstance(group, str) else list(group)
            names = [n.strip() for n in names if n.strip()]
            if not names:
                raise ValueError("--candidate-group: a group names no block")
            if any("," in n for n in names):
                raise ValueError("--candidate-group: a name with a comma cannot be passed to rbla")
            extra += ["--candidate-group", ",".join(names)]
        if cone_angle is not None:
            extra += ["--cone-angle", repr(float(cone_angle))]
        if tolerance is not None:
            extra += ["--tolerance", repr(float(tolerance))]
        if max_directions is not None:
            extra += ["--max-directions", str(int(max_directions))]
        return self._analysis("worst-settlement", extra, model, **_analysis_kwargs(kwargs))

    def critical_friction(self, model, target_alpha=None, tolerance=None, interfaces=None,
                          interfaces_of=None, **kwargs):
        """``rbla critical-friction``: the smallest factor on every friction coefficient (or on
        those of ``interfaces``, ids or labels, and of the interfaces touching the blocks
        ``interfaces_of``) at which the structure stands (or carries target_alpha). The
        outcome's result is the analysis at that factor; ``result.data["critical_friction"]``
        holds the search."""
        extra = []
        if target_alpha is not None:
            extra += ["--target-alpha", repr(float(target_alpha))]
        for option, names in (("--interfaces", interfaces), ("--interfaces-of", interfaces_of)):
            names = [names] if isinstance(names, str) else list(names or [])
            if any("," in n for n in names):
                raise ValueError("%s: a name with a comma cannot be passed to rbla" % option)
            if names:
                extra += [option, ",".join(names)]
        if tolerance is not None:
            extra += ["--tolerance", repr(float(tolerance))]
        return self._analysis("critical-friction", extra, model, **_analysis_kwargs(kwargs))

    def _analysis(self, command, extra, model, result_path=None, svg_dir=None, progress=None,
                  cancel=None, timeout=None, verbose=True, workdir=None, keep_files=False,
                  detail=None):
        if detail is not None and detail not in DETAILS:
            raise ValueError("detail: %r is not one of %s" % (detail, ", ".join(DETAILS)))
        tmp = tempfile.mkdtemp(prefix="rbla_", dir=workdir)
        try:
            model_path = _model_to_file(model, tmp)
            out_path = os.path.abspath(result_path) if result_path else \
                os.path.join(tmp, "result.json")
            args = [command, model_path, "-o", out_path] + list(extra)
            if svg_dir:
                args += ["--svg", os.path.abspath(svg_dir)]
            if verbose:
                args.append("-v")
            if detail is not None:
                args += ["--detail", detail]
            # A result already at result_path (an earlier run's) is not this run's answer: read
            # the file only when this run wrote it (the solver renames a new file into place).
            before = _file_identity(out_path)
            start = time.time()
            code, stdout, stderr = self._run(args, progress, cancel, timeout, tmp)
            seconds = time.time() - start
            result = None
            after = _file_identity(out_path)
            if code in (0, 3) and after is not None and after != before:
                with open(out_path, "r", encoding="utf-8") as f:
                    result = Result(json.load(f))
            verdict_line = stdout.strip().splitlines()[-1] if stdout.strip() else ""
            self._raise_for(code, stderr, result)
            if result is None:
                raise RblaError("the solver finished but wrote no result at %s" % out_path,
                                code, stderr)
            own_model = not model_path.startswith(tmp)
            return RunOutcome(result, code, verdict_line, stderr,
                              model_path if (keep_files or own_model) else None,
                              out_path if (keep_files or result_path) else None,
                              os.path.abspath(svg_dir) if svg_dir else None, seconds)
        finally:
            if not keep_files:
                shutil.rmtree(tmp, ignore_errors=True)

    def validate(self, model, progress=None, cancel=None, timeout=None):
        """``rbla validate``: return the solver's summary line; raise InvalidModelError."""
        tmp = tempfile.mkdtemp(prefix="rbla_")
        try:
            path = _model_to_file(model, tmp)
            code, stdout, stderr = self._run(["validate", path], progress, cancel, timeout, tmp)
            self._raise_for(code, stderr, None)
            return stdout.strip()
        finally:
            shutil.rmtree(tmp, ignore_errors=True)

    # ------------------------------------------------------------------------------------
    def _raise_for(self, code, stderr, result):
        if code == 0:
            return
        tail = _last_messages(stderr)
        if code == 1:
            raise UsageError("rbla usage error (exit 1): %s" % tail, code, stderr)
        if code == 2:
            issues = parse_invalid_report(stderr)
            if issues:
                text = "; ".join("%s: %s" % (p or "(document)", m) for p, m in issues[:10])
                if len(issues) > 10:
                    text += "; ... (%d issues)" % len(issues)
            else:
                text = tail
            raise InvalidModelError("invalid model: " + text, code, stderr, issues)
        if code == 3:
            what = result.verdict if result is not None else tail
            raise SolverFailureError("solver failure (exit 3): %s" % what, code, stderr, result)
        if code == 4:
            raise OutputError("the solver could not read or write a file (exit 4): %s" % tail,
                              code, stderr)
        raise RblaError("rbla stopped with exit code %s: %s" % (code, tail), code, stderr)

    def _run(self, args, progress, cancel, timeout, cwd):
        timeout = self.timeout if timeout is None else timeout
        cmd = [self.executable] + list(args)
        try:
            proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                    stderr=subprocess.PIPE, cwd=cwd, universal_newlines=True,
                                    bufsize=1, **_popen_extra())
        except OSError as e:
            raise SolverNotFoundError("cannot start %s: %s" % (self.executable, e))
        lines = queue.Queue()
        out_chunks = []
        err_lines = []

        def pump_err():
            for line in iter(proc.stderr.readline, ""):
                lines.put(line)
            lines.put(None)

        def pump_out():
            out_chunks.append(proc.stdout.read())

        threads = [threading.Thread(target=pump_err), threading.Thread(target=pump_out)]
        for t in threads:
            t.daemon = True
            t.start()
        deadline = None if not timeout else time.time() + float(timeout)
        stopped = None
        err_done = False

        def drain():
            done = False
            while True:
                try:
                    line = lines.get_nowait()
                except queue.Empty:
                    return done
                if line is None:
                    done = True
                    continue
                err_lines.append(line)
                if progress is not None:
                    progress(parse_stderr_line(line))

        try:
            while True:
                if _cancelled(cancel):
                    stopped = "cancel"
                    break
                if deadline is not None and time.time() > deadline:
                    stopped = "timeout"
                    break
                if drain():
                    err_done = True
                if proc.poll() is not None and (err_done or not threads[0].is_alive()):
                    break
                try:
                    line = lines.get(timeout=self.poll)
                except queue.Empty:
                    continue
                if line is None:
                    err_done = True
                else:
                    err_lines.append(line)
                    if progress is not None:
                        progress(parse_stderr_line(line))
        except BaseException:
            _stop(proc, self.grace)  # a callback raised (or Ctrl+C): never leave rbla running
            raise
        if stopped:
            _stop(proc, self.grace)
        for t in threads:
            t.join(5.0)
        drain()
        code = proc.wait()
        for stream in (proc.stdout, proc.stderr):
            try:
                stream.close()
            except (OSError, ValueError):
                pass
        stderr = "".join(err_lines)
        stdout = "".join(out_chunks)
        if stopped == "cancel":
            raise CancelledError("the solver run was cancelled", code, stderr)
        if stopped == "timeout":
            raise SolverTimeoutError("the solver did not finish within %g s and was stopped"
                                     % float(timeout), code, stderr)
        return code, stdout, stderr


_ANALYSIS_KWARGS = ("result_path", "svg_dir", "progress", "cancel", "timeout", "verbose", "workdir",
                    "keep_files", "detail")
# rbla's --detail levels (solver/src/io/result_writer.hpp, ResultDetail).
DETAILS = ("points", "interfaces", "blocks")


def _analysis_kwargs(kwargs):
    unknown = set(kwargs) - set(_ANALYSIS_KWARGS)
    if unknown:
        raise TypeError("unexpected keyword arguments: %s" % ", ".join(sorted(unknown)))
    return kwargs


def _file_identity(path):
    """What tells one version of a regular file from another (device, inode, size, times), or
    None when there is no regular file at path."""
    try:
        st = os.stat(path)
    except OSError:
        return None
    if not stat.S_ISREG(st.st_mode):
        return None
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns, st.st_ctime_ns)


def _cancelled(cancel):
    if cancel is None:
        return False
    if hasattr(cancel, "is_set"):
        return cancel.is_set()
    return bool(cancel())


def _stop(proc, grace):
    try:
        proc.terminate()
    except OSError:
        return
    end = time.time() + grace
    while time.time() < end:
        if proc.poll() is not None:
            return
        time.sleep(0.02)
    try:
        proc.kill()
    except OSError:
        pass


def _popen_extra():
    """No console window flashing up when a GUI host (Rhino on Windows) starts rbla."""
    if sys.platform.startswith("win"):
        return {"creationflags": getattr(subprocess, "CREATE_NO_WINDOW", 0x08000000)}
    return {}


def _last_messages(stderr, n=3):
    lines = [l.strip() for l in stderr.splitlines() if l.strip()]
    if not lines:
        return "(no message)"
    return " | ".join(lines[-n:])
