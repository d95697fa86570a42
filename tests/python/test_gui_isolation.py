"""The GUI tests' FreeCAD is hermetic (tests/run_all.py gui_env): it reads its own
user settings and Mod folder, so a Tessella copy installed in the user's Mod
folder (as `make install` does) is neither loaded nor the copy under test. A
decoy "installed copy" in a stand-in user home would write a marker when
FreeCAD loads it; under gui_env it must not."""

import importlib.util
import json
import os
import shutil
import subprocess
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def load_run_all():
    spec = importlib.util.spec_from_file_location("run_all", os.path.join(REPO, "tests", "run_all.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.skipif(shutil.which("xvfb-run") is None or shutil.which("freecad") is None,
                    reason="needs xvfb-run and the FreeCAD GUI")
def test_gui_tests_do_not_see_the_users_mod_folder(tmp_path, monkeypatch):
    user = tmp_path / "user"
    marker = tmp_path / "decoy_loaded"
    for mod in (user / ".local/share/FreeCAD/Mod/Tessella", user / ".FreeCAD/Mod/Tessella"):
        mod.mkdir(parents=True)
        (mod / "Init.py").write_text(f"open({str(marker)!r}, 'w').write('loaded')\n")
        (mod / "InitGui.py").write_text(f"open({str(marker)!r}, 'w').write('loaded')\n")
    monkeypatch.setenv("HOME", str(user))
    probe = tmp_path / "probe.py"
    out = tmp_path / "probe.json"
    probe.write_text(
        "import json, os, FreeCAD\n"
        f"json.dump({{'data': FreeCAD.getUserAppDataDir()}}, open({str(out)!r}, 'w'))\n"
        "os._exit(0)\n")
    env = load_run_all().gui_env(tmp_path / "gui")
    subprocess.run(["xvfb-run", "-a", "freecad", str(probe)], env=env, timeout=300,
                   stdin=subprocess.DEVNULL, capture_output=True)
    data = json.loads(out.read_text())
    assert data["data"].startswith(str(tmp_path / "gui")), data
    assert not marker.exists(), "FreeCAD loaded the Tessella copy in the user's Mod folder"
