"""The COMPAS converter's command line reads and writes files as the solver does (rbla_cad.safe_files):
the output is never the input, a folder or a replaced device; pipes and character devices are
written into, links followed, files replaced atomically with their permission bits; devices,
folders and huge files are refused as input; bad option values and deep nesting give one line and
an exit code, never a traceback (1 bad option, 2 invalid input, 4 a file error).
"""

import json
import os
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import threading
import unittest
from unittest import mock

import _support
from rbla_cad import safe_files

ARCH = os.path.join(_support.REPO, "tests", "data", "compas", "compas_assembly", "arch_assembly.json")


def _limit_memory():
    # a converter that reads /dev/zero to the end fails here instead of taking the machine's memory
    import resource
    resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))


def convert(*args, stdin=None):
    r = subprocess.run([sys.executable, "-m", "rbla_cad.compas_import"] + list(args), cwd=_support.PLUGIN,
                       input=stdin, capture_output=True, timeout=60,
                       preexec_fn=_limit_memory if os.name == "posix" else None)
    return r.returncode, r.stdout, r.stderr.decode("utf-8", "replace")


def device(folder, name, minor):
    """A character device like /dev/<name> (Linux major 1). As root, a new node in folder, so a
    converter that replaced its output would replace only the copy; else the real one, which
    only root could replace."""
    real = "/dev/" + name
    if hasattr(os, "geteuid") and os.geteuid() == 0 and hasattr(os, "mknod"):
        path = os.path.join(folder, name)
        try:
            os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, minor))
            return path
        except OSError:
            pass
        raise unittest.SkipTest("cannot make a device node in %s" % folder)
    if not os.path.exists(real):
        raise unittest.SkipTest("no " + real)
    return real


def read_fifo(path, got):
    with open(path, "rb") as f:
        got.append(f.read())


class CompasImportFilesTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()
        self.input = os.path.join(self.dir, "in.json")
        shutil.copyfile(ARCH, self.input)
        with open(ARCH, "rb") as f:
            self.original = f.read()

    def tearDown(self):
        shutil.rmtree(self.dir)

    def path(self, name):
        return os.path.join(self.dir, name)

    def assertRefused(self, result, code, *words):
        rc, _, err = result
        self.assertEqual(rc, code, err)
        self.assertNotIn("Traceback", err)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        for w in words:
            self.assertIn(w, err)

    def assertInputIntact(self):
        with open(self.input, "rb") as f:
            self.assertEqual(f.read(), self.original)

    def assertNoTemporaryFiles(self, folder=None):
        left = [n for n in os.listdir(folder or self.dir) if ".tmp" in n]
        self.assertEqual(left, [])

    # ---- outputs ----------------------------------------------------------------------------
    def test_output_that_is_the_input_is_refused_however_spelled(self):
        os.symlink("in.json", self.path("link.json"))
        os.link(self.input, self.path("hard.json"))
        spellings = [self.input, os.path.join(self.dir, ".", "in.json"), self.path("link.json"),
                     self.path("hard.json")]
        for out in spellings:
            self.assertRefused(convert(self.input, "-o", out), 4, out, "input")
        self.assertRefused(convert(self.path("link.json"), "-o", self.input), 4, "input")
        self.assertInputIntact()
        self.assertTrue(os.path.islink(self.path("link.json")))

    def test_output_folder_is_refused_and_leaves_no_temporary_file(self):
        out = self.path("folder")
        os.mkdir(out)
        self.assertRefused(convert(self.input, "-o", out), 4, out, "directory")
        self.assertRefused(convert(self.input, "-o", out + "/"), 4, "directory")
        self.assertFalse(os.path.exists(out + ".tmp"))
        self.assertNoTemporaryFiles()
        self.assertEqual(os.listdir(out), [])

    def test_a_full_device_is_written_into_never_replaced(self):
        full = device(self.dir, "full", 7)
        self.assertRefused(convert(self.input, "-o", full), 4, full, "No space")
        self.assertTrue(stat.S_ISCHR(os.lstat(full).st_mode))
        self.assertNoTemporaryFiles()

    def test_a_null_device_is_written_into_never_replaced(self):
        null = device(self.dir, "null", 3)
        rc, _, err = convert(self.input, "-o", null)
        self.assertEqual(rc, 0, err)
        self.assertTrue(stat.S_ISCHR(os.lstat(null).st_mode))

    @unittest.skipUnless(hasattr(os, "mkfifo"), "no FIFOs")
    def test_a_fifo_is_written_into(self):
        fifo = self.path("pipe")
        os.mkfifo(fifo)
        got = []
        reader = threading.Thread(target=read_fifo, args=(fifo, got), daemon=True)
        reader.start()
        rc, _, err = convert(self.input, "-o", fifo)
        if not got and reader.is_alive():  # the converter never opened it: let the reader go
            os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
        reader.join(30)
        self.assertEqual(rc, 0, err)
        self.assertEqual(len(json.loads(got[0].decode())["blocks"]), 30)
        self.assertTrue(stat.S_ISFIFO(os.lstat(fifo).st_mode))

    def test_a_link_is_followed_and_its_target_written(self):
        target = self.path("target.json")
        with open(target, "w") as f:
            f.write("old\n")
        os.symlink("target.json", self.path("link.json"))
        os.symlink("missing.json", self.path("dangling.json"))
        for link in ("link.json", "dangling.json"):
            rc, _, err = convert(self.input, "-o", self.path(link))
            self.assertEqual(rc, 0, err)
            self.assertTrue(os.path.islink(self.path(link)))
        for name in ("target.json", "missing.json"):
            with open(self.path(name)) as f:
                self.assertEqual(len(json.load(f)["blocks"]), 30)
        self.assertNoTemporaryFiles()

    def test_a_replaced_file_keeps_its_permission_bits(self):
        out = self.path("out.json")
        with open(out, "w") as f:
            f.write("old\n")
        os.chmod(out, 0o640)
        rc, _, err = convert(self.input, "-o", out)
        self.assertEqual(rc, 0, err)
        self.assertEqual(stat.S_IMODE(os.stat(out).st_mode), 0o640)
        with open(out) as f:
            self.assertEqual(len(json.load(f)["blocks"]), 30)

    @unittest.skipIf(not hasattr(os, "geteuid") or os.geteuid() == 0, "root may write anything")
    def test_a_read_only_file_or_folder_is_refused(self):
        out = self.path("readonly.json")
        with open(out, "w") as f:
            f.write("old\n")
        os.chmod(out, 0o444)
        self.assertRefused(convert(self.input, "-o", out), 4, out)
        with open(out) as f:
            self.assertEqual(f.read(), "old\n")
        folder = self.path("locked")
        os.mkdir(folder)
        os.chmod(folder, 0o555)
        try:
            self.assertRefused(convert(self.input, "-o", os.path.join(folder, "m.json")), 4, "folder")
        finally:
            os.chmod(folder, 0o755)

    def test_stdout_by_default_and_with_dash(self):
        for args in ([], ["-o", "-"]):
            rc, out, err = convert(self.input, *args)
            self.assertEqual(rc, 0, err)
            self.assertEqual(len(json.loads(out.decode())["blocks"]), 30)

    # ---- inputs -----------------------------------------------------------------------------
    def test_devices_and_folders_are_refused_as_input_before_reading(self):
        zero = device(self.dir, "zero", 5)
        for bad, word in ((zero, "character device"), (self.dir, "directory")):
            self.assertRefused(convert(bad, "-o", self.path("m.json")), 4, bad, word)
        self.assertFalse(os.path.exists(self.path("m.json")))

    def test_an_input_above_the_limit_is_refused(self):
        self.assertRefused(convert(self.input, "--max-input-bytes", "1000"), 4, self.input, "limit")
        # standard input has no size: it is read with the cap
        self.assertRefused(convert("-", "--max-input-bytes", "1000", stdin=self.original), 4,
                           "standard input", "limit")
        rc, out, err = convert("-", stdin=self.original)
        self.assertEqual(rc, 0, err)

    def test_node_ids_with_control_characters_cannot_forge_report_lines(self):
        # Block ids are the file's node keys: a newline or a terminal escape in one is printed
        # escaped, so the report keeps its own lines and the terminal its state.
        with open(ARCH) as f:
            doc = json.load(f)
        graph = doc["data"]["graph"]["data"]
        forged = "0\nrbla: solved, alpha = 9\x1b[2J"
        graph["node"][forged] = graph["node"].pop("0")
        for edge in graph["edge"].values():
            if "0" in edge:
                edge[forged] = edge.pop("0")
        if "0" in graph["edge"]:
            graph["edge"][forged] = graph["edge"].pop("0")
        code, out, err = convert("-", stdin=json.dumps(doc).encode())
        self.assertEqual(code, 0, err)
        self.assertNotIn("\x1b", err)
        self.assertFalse(any(line.startswith("rbla: solved") for line in err.splitlines()), err)
        self.assertIn("0\\nrbla: solved, alpha = 9\\x1b[2J", err)
        self.assertIn(forged, [b["id"] for b in json.loads(out)["blocks"]])

    def test_deep_nesting_is_invalid_input_without_a_traceback(self):
        deep = self.path("deep.json")
        with open(deep, "w") as f:
            f.write("[" * 200000 + "]" * 200000)
        self.assertRefused(convert(deep, "-o", self.path("m.json")), 2, "too deeply nested")
        self.assertFalse(os.path.exists(self.path("m.json")))

    def test_malformed_values_are_refused_with_their_pointer_without_a_traceback(self):
        # well-nested JSON of the right layout, wrong inside: before, a Python traceback
        with open(self.input) as f:
            arch = json.load(f)
        cases = [("vertices as text", "/data/graph/data/node/3/block/data/vertex/2",
                  lambda d: d["block"]["data"]["vertex"].__setitem__("2", "1 2 3")),
                 ("face out of range", "/data/graph/data/node/3/block/data/face/1/0",
                  lambda d: d["block"]["data"]["face"]["1"].__setitem__(0, 12345)),
                 ("number for a mesh's faces", "/data/graph/data/node/3/block/data/face",
                  lambda d: d["block"]["data"].__setitem__("face", 6)),
                 ("number for a node", "/data/graph/data/node/3", None)]
        out = self.path("m.json")
        for name, pointer, spoil in cases:
            with self.subTest(name):
                doc = json.loads(json.dumps(arch))
                target = doc["data"]["graph"]["data"]["node"]
                if spoil is None:
                    target["3"] = 7
                else:
                    spoil(target["3"])
                bad = self.path("bad.json")
                with open(bad, "w") as f:
                    json.dump(doc, f)
                self.assertRefused(convert(bad, "-o", out), 1, "%s: cannot convert: %s: " % (bad, pointer))
                self.assertFalse(os.path.exists(out))

    # ---- options ----------------------------------------------------------------------------
    def test_option_values_outside_the_schema_ranges_are_refused(self):
        out = self.path("m.json")
        for option, value in (("--unit-weight", "nan"), ("--unit-weight", "inf"), ("--unit-weight", "0"),
                              ("--unit-weight", "-18"), ("--friction", "-1"), ("--friction", "0"),
                              ("--friction", "nan"), ("--friction", "101"), ("--friction", "x")):
            self.assertRefused(convert(self.input, "-o", out, option, value), 1, option)
        self.assertFalse(os.path.exists(out))
        rc, _, err = convert(self.input, "-o", out, "--friction", "100", "--unit-weight", "25")
        self.assertEqual(rc, 0, err)
        with open(out) as f:
            self.assertEqual(json.load(f)["defaults"], {"unit_weight": 25.0, "friction": 100.0})


class SafeFilesTest(unittest.TestCase):
    """The helper itself: a failed write leaves the old file and no temporary file."""

    def setUp(self):
        self.dir = tempfile.mkdtemp()

    def tearDown(self):
        shutil.rmtree(self.dir)

    def test_a_failed_write_removes_its_temporary_file(self):
        out = os.path.join(self.dir, "out.json")
        with open(out, "w") as f:
            f.write("old\n")
        with mock.patch.object(safe_files.os, "fsync", side_effect=OSError(5, "Input/output error")):
            with self.assertRaises(safe_files.FileError) as cm:
                safe_files.write_output(out, "new\n")
        self.assertIn(out, str(cm.exception))
        self.assertEqual(os.listdir(self.dir), ["out.json"])
        with open(out) as f:
            self.assertEqual(f.read(), "old\n")

    def test_a_new_file_is_written_with_the_usual_permissions(self):
        out = os.path.join(self.dir, "new.json")
        safe_files.write_output(out, "x\n")
        mask = os.umask(0)
        os.umask(mask)
        self.assertEqual(stat.S_IMODE(os.stat(out).st_mode), 0o666 & ~mask)

    def test_a_replaced_file_keeps_its_owner_and_group_where_allowed(self):
        out = os.path.join(self.dir, "owned.json")
        with open(out, "w") as f:
            f.write("old\n")
        if os.geteuid() == 0:
            owner = (4321, 4322)  # root may give the new file anyone's
        else:
            others = [g for g in os.getgroups() if g != os.getegid()]
            if not others:
                self.skipTest("not root and in no second group: nothing to keep")
            owner = (os.geteuid(), others[0])
        os.chown(out, *owner)
        safe_files.write_output(out, "new\n")
        st = os.stat(out)
        self.assertEqual((st.st_uid, st.st_gid), owner)
        with open(out) as f:
            self.assertEqual(f.read(), "new\n")

    # A writer that signals itself just after flushing its temporary file, as a kill would.
    SIGNALLED_WRITER = """
import os, signal, sys
sys.path.insert(0, sys.argv[1])
from rbla_cad import safe_files
sig = int(sys.argv[3])
if sys.argv[4] == "ignored":
    signal.signal(sig, signal.SIG_IGN)  # as under nohup: not ours to change
fsync = os.fsync
def fsync_then_signal(fd):
    fsync(fd)
    os.kill(os.getpid(), sig)
os.fsync = fsync_then_signal
safe_files.write_output(sys.argv[2], "new\\n")
print("survived")
"""

    @unittest.skipUnless(hasattr(signal, "SIGHUP"), "POSIX signals")
    def test_a_signal_mid_write_removes_the_temporary_file_and_still_ends_the_process(self):
        out = os.path.join(self.dir, "out.json")
        for sig in (signal.SIGTERM, signal.SIGHUP, signal.SIGINT):
            with self.subTest(signal=sig.name):
                with open(out, "w") as f:
                    f.write("old\n")
                r = subprocess.run([sys.executable, "-c", self.SIGNALLED_WRITER, _support.PLUGIN, out,
                                    str(int(sig)), "default"], capture_output=True, timeout=60)
                self.assertEqual(r.returncode, -sig, r.stderr)  # ended by the signal, as without us
                self.assertEqual(os.listdir(self.dir), ["out.json"])
                with open(out) as f:
                    self.assertEqual(f.read(), "old\n")
        # an ignored signal stays ignored: the write completes
        r = subprocess.run([sys.executable, "-c", self.SIGNALLED_WRITER, _support.PLUGIN, out,
                            str(int(signal.SIGHUP)), "ignored"], capture_output=True, timeout=60)
        self.assertEqual((r.returncode, r.stdout.strip()), (0, b"survived"), r.stderr)
        with open(out) as f:
            self.assertEqual(f.read(), "new\n")

    def test_the_signal_handlers_are_put_back_after_a_write(self):
        before = {sig: signal.getsignal(sig) for sig in safe_files._SIGNALS}
        safe_files.write_output(os.path.join(self.dir, "x.json"), "x\n")
        self.assertEqual({sig: signal.getsignal(sig) for sig in safe_files._SIGNALS}, before)

    def test_missing_folder_and_empty_path_are_refused(self):
        for bad in ("", os.path.join(self.dir, "no", "such", "x.json")):
            with self.assertRaises(safe_files.FileError):
                safe_files.resolve_output(bad)


if __name__ == "__main__":
    unittest.main()
