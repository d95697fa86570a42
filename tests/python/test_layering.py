"""Layering rules of the Python package, checked on the source (ast) and at run time.

features/ (App proxies, module paths frozen in .FCStd files) must not import the
GUI: neither freecad_workbench.gui (relative or absolute) nor FreeCADGui. The GUI
reaches the features through features.base.view_provider_hook instead.
"""
import ast
import os
import subprocess
import sys
import types
from pathlib import Path

import FreeCAD
import pytest

ROOT = Path(__file__).resolve().parents[2]
FEATURES = ROOT / "freecad_workbench" / "features"


def _gui_imports(path):
    """(line, text) of every import of the GUI in one source file."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    found = []

    def bad_module(name):
        parts = (name or "").split(".")
        return parts[0] == "FreeCADGui" or parts[0] == "gui" or parts[:2] == [
            "freecad_workbench", "gui"]

    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if bad_module(alias.name):
                    found.append((node.lineno, f"import {alias.name}"))
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            names = [a.name for a in node.names]
            if node.level == 0:
                # absolute: from freecad_workbench.gui import x, from freecad_workbench import gui
                if bad_module(module) or (module == "freecad_workbench" and "gui" in names):
                    found.append((node.lineno, f"from {module} import {names}"))
            else:
                # relative: from ..gui import x, from .. import gui, from ..gui.view_providers ...
                if module.split(".")[0] == "gui" or (not module and "gui" in names):
                    found.append((node.lineno, f"from {'.' * node.level}{module} import {names}"))
        elif isinstance(node, ast.Call):
            # importlib.import_module("...gui...") / __import__("FreeCADGui")
            func = node.func
            name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
            if name in ("import_module", "__import__") and node.args:
                arg = node.args[0]
                if isinstance(arg, ast.Constant) and isinstance(arg.value, str) and (
                        "FreeCADGui" in arg.value or "gui" in arg.value.split(".")):
                    found.append((node.lineno, f"{name}({arg.value!r})"))
        elif isinstance(node, ast.Name) and node.id == "FreeCADGui":
            found.append((node.lineno, "FreeCADGui used"))
    return found


def test_features_import_nothing_from_the_gui():
    files = sorted(FEATURES.glob("*.py"))
    assert len(files) >= 4  # __init__, base, panelization, unfold, curve_network
    offending = {f.name: hits for f in files if (hits := _gui_imports(f))}
    assert not offending, f"features/ imports the GUI: {offending}"


@pytest.mark.parametrize("source, bad", [
    ("from ..gui import view_providers", True),
    ("from .. import gui", True),
    ("from ..gui.unfold_view import ViewProviderUnfold", True),
    ("import freecad_workbench.gui.view_providers", True),
    ("from freecad_workbench.gui import commands", True),
    ("from freecad_workbench import gui", True),
    ("import FreeCADGui as Gui", True),
    ("from FreeCADGui import Selection", True),
    ("importlib.import_module('freecad_workbench.gui')", True),
    ("from .base import add_property", False),
    ("from .. import api", False),
    ("import FreeCAD", False),
    ("from ..guides import x", False),
])
def test_the_scanner_sees_every_form(tmp_path, source, bad):
    path = tmp_path / "probe.py"
    path.write_text(source + "\n")
    assert bool(_gui_imports(path)) == bad


def test_importing_and_using_the_features_loads_no_gui_module():
    script = (
        "import sys\n"
        f"sys.path[:0] = ['/usr/lib/freecad-python3/lib', {str(ROOT)!r}]\n"
        "import FreeCAD, Part\n"
        "import freecad_workbench as tessella\n"
        "from freecad_workbench.features import base, curve_network, panelization, unfold\n"
        "doc = FreeCAD.newDocument('Layering')\n"
        "src = doc.addObject('Part::Feature', 'Plate')\n"
        "src.Shape = Part.makePlane(4000, 3000)\n"
        "p = tessella.make_panelization((src, 'Face1'), size=1000.0)\n"
        "tessella.make_unfold(p)\n"
        "bad = sorted(m for m in sys.modules if m.startswith('freecad_workbench.gui')\n"
        "             or m == 'FreeCADGui')\n"
        "assert not bad, bad\n"
        "assert base.view_provider_hook is None\n"
        "print('ok')\n"
    )
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=300, env=dict(os.environ, PYTHONPATH=""))
    assert proc.returncode == 0 and "ok" in proc.stdout, proc.stderr[-2000:]


class _FakeViewObject:
    Proxy = None


def test_view_provider_hook(monkeypatch):
    from freecad_workbench.features import base

    calls = []
    obj = types.SimpleNamespace(Label="P", ViewObject=_FakeViewObject())
    monkeypatch.setattr(base, "view_provider_hook", lambda vobj, name: calls.append((vobj, name)))
    base._attach_view_provider(obj, "ViewProviderPanelization")
    assert calls == []  # headless: nothing is attached
    monkeypatch.setattr(FreeCAD, "GuiUp", 1, raising=False)
    base._attach_view_provider(obj, "ViewProviderPanelization")
    assert calls == [(obj.ViewObject, "ViewProviderPanelization")]
    obj.ViewObject.Proxy = object()  # already has one: left alone
    base._attach_view_provider(obj, "ViewProviderPanelization")
    assert len(calls) == 1

    def broken(vobj, name):
        raise RuntimeError("no icon")

    obj.ViewObject.Proxy = None
    monkeypatch.setattr(base, "view_provider_hook", broken)
    base._attach_view_provider(obj, "ViewProviderPanelization")  # warns, never raises
    monkeypatch.setattr(base, "view_provider_hook", None)
    base._attach_view_provider(obj, "ViewProviderPanelization")  # GUI package not loaded


def test_the_gui_package_installs_the_hook(monkeypatch):
    from freecad_workbench.features import base

    monkeypatch.setattr(base, "view_provider_hook", None)
    import freecad_workbench.gui as gui

    gui.install_hooks()
    assert base.view_provider_hook is gui.attach_view_provider
    with pytest.raises(LookupError):
        gui.attach_view_provider(_FakeViewObject(), "NoSuchViewProvider")


GUI = ROOT / "freecad_workbench" / "gui"
COMMAND_MODULES = ("commands", "analysis_commands", "fabrication_commands")


def _relative_imports(path):
    """Module names (within gui/) a gui module imports at any level of its code."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            if node.module:
                names.add(node.module.split(".")[0])
            else:
                names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            parts = node.module.split(".")
            if parts[:2] == ["freecad_workbench", "gui"]:
                names.add(parts[2] if len(parts) > 2 else "")
                if len(parts) == 2:
                    names.update(a.name for a in node.names)
        elif isinstance(node, ast.Import):
            for alias in node.names:
                parts = alias.name.split(".")
                if parts[:2] == ["freecad_workbench", "gui"] and len(parts) > 2:
                    names.add(parts[2])
    return names


def test_command_modules_import_only_common_not_each_other():
    for name in COMMAND_MODULES:
        imported = _relative_imports(GUI / f"{name}.py")
        others = imported & (set(COMMAND_MODULES) - {name})
        assert not others, f"gui/{name}.py imports {sorted(others)}"
        assert "common" in imported, f"gui/{name}.py does not use gui/common.py"
    assert _relative_imports(GUI / "common.py").isdisjoint(COMMAND_MODULES)
    # one place registers them all, and InitGui.py goes through it
    assert set(COMMAND_MODULES) <= _relative_imports(GUI / "register.py")
    init_gui = (ROOT / "InitGui.py").read_text(encoding="utf-8")
    assert "from freecad_workbench.gui import register" in init_gui
    # the menu and toolbar: register.MENU, each module's COMMANDS in turn, in groups
    assert "register.MENU" in init_gui
    register = (GUI / "register.py").read_text(encoding="utf-8")
    menu = register[register.index("MENU = "):]
    for name in ("commands", "analysis_commands", "fabrication_commands"):
        assert f"{name}.COMMANDS" in menu, name


def test_command_icons_exist():
    from freecad_workbench.gui import common

    icons = set()
    for name in COMMAND_MODULES:
        tree = ast.parse((GUI / f"{name}.py").read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Assign) and any(
                    getattr(t, "id", None) == "ICON" for t in node.targets):
                icons.add(node.value.value)
    assert len(icons) >= 4
    for icon in icons:
        assert os.path.isfile(common.icon_path(icon)), icon
    from freecad_workbench.gui import view_providers

    assert view_providers.icon_path is common.icon_path  # the old import path
