"""What every GUI test script shares: check() bookkeeping, event processing,
closing message boxes, registering the workbench, and writing the result file
that tests/run_all.py reads before FreeCAD is quit."""

import json
import os
import sys
import tempfile
import traceback

import FreeCAD
import FreeCADGui as Gui

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = (os.environ.get("TESSELLA_ROOT") or os.environ.get("TESSELLA_REPO")
        or os.path.dirname(os.path.dirname(HERE)))

results = {"passed": 0, "failed": 0, "failures": [], "checks": [], "registration": None}


def check(name, condition, detail=""):
    results["checks"].append(name)
    if condition:
        results["passed"] += 1
    else:
        results["failed"] += 1
        results["failures"].append(f"{name}: {detail}" if detail else name)
    return bool(condition)


class recorded_commands:
    """`with recorded_commands() as lines:` every line run through Gui.doCommand
    meanwhile (still run), for checking what the console and a macro see."""

    def __enter__(self):
        self.lines = []
        self.original = Gui.doCommand

        def record(line):
            self.lines.append(line)
            return self.original(line)

        Gui.doCommand = record
        return self.lines

    def __exit__(self, *exc):
        Gui.doCommand = self.original
        return False


def command_active(name):
    """Whether FreeCAD shows command `name` enabled (its IsActive) right now."""
    process_events()
    return bool(Gui.Command.get(name).isActive())


def process_events():
    from PySide import QtGui

    QtGui.QApplication.processEvents()


class DialogCatcher:
    """Closes modal message boxes while a command runs and remembers their text."""

    def __init__(self):
        from PySide import QtCore

        self.texts = []
        self.timer = QtCore.QTimer()
        self.timer.setInterval(50)
        self.timer.timeout.connect(self._close)

    def _close(self):
        from PySide import QtGui

        w = QtGui.QApplication.activeModalWidget()
        if w is not None and isinstance(w, QtGui.QMessageBox):
            self.texts.append(w.text())
            w.done(0)

    def __enter__(self):
        self.texts.clear()
        self.timer.start()
        return self

    def __exit__(self, *exc):
        process_events()
        self.timer.stop()
        return False


def ensure_workbench():
    if "TessellaWorkbench" in Gui.listWorkbenches():
        results["registration"] = "Mod folder"
        return
    # What FreeCAD does for a Mod folder: the folder on sys.path, InitGui.py
    # exec()'d with names that its functions cannot see (strict: empty globals).
    if REPO not in sys.path:
        sys.path.insert(0, REPO)
    with open(os.path.join(REPO, "InitGui.py"), encoding="utf-8") as f:
        source = f.read()
    exec(compile(source, os.path.join(REPO, "InitGui.py"), "exec"),
         {"__builtins__": __builtins__}, {})
    results["registration"] = "manual (InitGui.py executed by the test)"


def run(title, tests, default_result):
    """Run the test functions, write $TESSELLA_GUI_RESULT (or default_result in
    the temp folder) and quit FreeCAD without save prompts."""
    path = os.environ.get("TESSELLA_GUI_RESULT") or os.path.join(
        tempfile.gettempdir(), default_result)
    try:
        for test in tests:
            try:
                test()
            except Exception:
                check(test.__name__ + " raised", False, traceback.format_exc())
        with open(path, "w", encoding="utf-8") as f:
            json.dump(results, f, indent=1)
        FreeCAD.Console.PrintMessage(
            f"{title}: {results['passed']} passed, {results['failed']} failed\n")
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(0 if results["failed"] == 0 else 1)
