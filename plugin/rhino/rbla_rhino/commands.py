"""Bodies of the Rhino commands (the scripts in plugin/rhino/commands/ call these).

RblaExport          write the model JSON (selected objects, or all) and report bad blocks
RblaSolve           export, run the solver (Esc cancels; progress on the status bar), draw
RblaShowMechanism   redraw the last result at an amplitude (option: hinge-exact screw motion)
RblaClear           delete the drawn results (undoable)

Each returns a Rhino.Commands.Result.
"""

import json
import os

import Rhino

from rbla_cad import runner as rrun
from rbla_cad.model import ModelError, load_model
from rbla_cad.result import load_result

from . import document as rdoc

Result = Rhino.Commands.Result


def _say(text):
    Rhino.RhinoApp.WriteLine("rbla: " + text)


def _export(doc):
    """Collect and write the model; returns (model dict, path, collected) or None. Prints the
    reader's warnings, and every error when there is one (then nothing is written)."""
    col = rdoc.collect_model(doc)
    for m in col.messages:
        if m.severity == "warning":
            _say("warning [%s]: %s" % (m.code, m.text))
    errors = [m for m in col.messages if m.severity == "error"]
    if errors:
        _say("the model cannot be exported (%d error%s):"
             % (len(errors), "" if len(errors) == 1 else "s"))
        for m in errors:
            for k, line in enumerate(m.text.splitlines()):
                Rhino.RhinoApp.WriteLine(("  error [%s]: " % m.code if k == 0 else "    ") + line)
        return None
    model = col.model
    folder = rdoc.run_folder(doc)
    path = os.path.join(folder, "model.json")
    col.builder.write(path)
    rdoc.remember(doc, model_path=path, result_path="")
    _say("wrote %s (%d blocks, %d interfaces given, units %s/%s%s)"
         % (path, len(model["blocks"]), len(model.get("interfaces", [])),
            model["units"]["length"], model["units"]["force"],
            "" if col.builder.length_scale == 1 else
            ", document coordinates x %g" % col.builder.length_scale))
    return model, path, col


def export_command():
    doc = rdoc.active_doc()
    return Result.Success if _export(doc) else Result.Failure


class _EscapeWatch(object):
    """Cancel callable for the runner: pumps Rhino's message loop and reports Esc."""

    def __init__(self):
        self.pressed = False
        self._handler = self._on_escape  # keep one object: -= needs the same delegate
        Rhino.RhinoApp.EscapeKeyPressed += self._handler

    def _on_escape(self, sender, args):
        self.pressed = True

    def __call__(self):
        Rhino.RhinoApp.Wait()
        return self.pressed

    def close(self):
        Rhino.RhinoApp.EscapeKeyPressed -= self._handler


def solve_command(amplitude=None):
    doc = rdoc.active_doc()
    exported = _export(doc)
    if not exported:
        return Result.Failure
    model, path, col = exported
    try:
        runner = rrun.Runner(col.settings.get("exe"))
    except rrun.SolverNotFoundError as e:
        _say(str(e))
        return Result.Failure
    folder = os.path.dirname(path)
    result_path = os.path.join(folder, "result.json")
    watch = _EscapeWatch()
    meter = {"on": False}

    def progress(ev):
        if ev.kind == "stage":
            Rhino.RhinoApp.SetCommandPrompt("rbla: " + ev.text[:120] + "  (Esc cancels)")
            _say(ev.text)
        elif ev.kind == "warning":
            _say(ev.text)
        elif ev.kind == "iteration":
            if not meter["on"]:
                Rhino.UI.StatusBar.ShowProgressMeter(0, 100, "rbla interior point", True, True)
                meter["on"] = True
            Rhino.UI.StatusBar.UpdateProgressMeter(min(ev.data["iteration"], 100), True)
    try:
        outcome = runner.solve(path, result_path=result_path,
                               svg_dir=os.path.join(folder, "svg"), progress=progress,
                               cancel=watch)
    except rrun.CancelledError:
        _say("cancelled")
        return Result.Cancel
    except rrun.InvalidModelError as e:
        _say("the solver rejected the model:")
        for ptr, msg in e.issues or [("", str(e))]:
            Rhino.RhinoApp.WriteLine("  %s: %s" % (ptr or "(document)", msg))
        return Result.Failure
    except rrun.SolverFailureError as e:
        _say(str(e))
        if e.result is not None:
            rdoc.remember(doc, result_path=result_path)
        return Result.Failure
    except rrun.RblaError as e:
        _say(str(e))
        return Result.Failure
    finally:
        watch.close()
        if meter["on"]:
            Rhino.UI.StatusBar.HideProgressMeter()
    rdoc.remember(doc, result_path=result_path)
    res = outcome.result
    _say(res.verdict)
    _say("result: %s (%.2f s)" % (result_path, outcome.seconds))
    s = rdoc.draw_result(doc, model, res, amplitude, block_objects=col.block_objects)
    _say("mechanism drawn at amplitude %g on layer '%s'" % (s, rdoc.RESULT_LAYER))
    return Result.Success


def show_mechanism_command():
    doc = rdoc.active_doc()
    mpath, rpath = rdoc.recall(doc, "model_path"), rdoc.recall(doc, "result_path")
    if not mpath or not rpath or not os.path.isfile(mpath) or not os.path.isfile(rpath):
        _say("no result yet: run RblaSolve first")
        return Result.Nothing
    model = load_model(mpath)
    res = load_result(rpath)
    gp = Rhino.Input.Custom.GetNumber()
    gp.SetCommandPrompt("Display amplitude (solver suggests %g)" % res.displacement_scale)
    gp.SetDefaultNumber(res.displacement_scale)
    gp.SetLowerLimit(0.0, False)
    screw = Rhino.Input.Custom.OptionToggle(False, "AboutCentroid", "HingeExact")
    closed = Rhino.Input.Custom.OptionToggle(False, "No", "Yes")
    gp.AddOptionToggle("Motion", screw)
    gp.AddOptionToggle("ClosedContacts", closed)
    gp.AcceptNothing(True)
    while True:
        r = gp.Get()
        if r == Rhino.Input.GetResult.Option:
            continue
        if r in (Rhino.Input.GetResult.Number, Rhino.Input.GetResult.Nothing):
            break
        return Result.Cancel
    amplitude = gp.Number() if r == Rhino.Input.GetResult.Number else res.displacement_scale
    try:
        s = rdoc.draw_result(doc, model, res, amplitude, screw=screw.CurrentValue,
                             show_closed=closed.CurrentValue)
    except ModelError as e:
        _say(str(e))
        return Result.Failure
    _say("%s; drawn at amplitude %g" % (res.headline(), s))
    return Result.Success


def clear_command():
    doc = rdoc.active_doc()
    n = rdoc.clear_results(doc)
    _say("deleted %d result object%s" % (n, "" if n == 1 else "s"))
    return Result.Success


def model_json_text(doc=None):
    """The model JSON text of the document (for scripting)."""
    col = rdoc.collect_model(doc or rdoc.active_doc())
    if col.issues:
        raise ModelError("\n".join(col.issues))
    return json.dumps(col.model, indent=1)
