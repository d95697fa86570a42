#!/usr/bin/env python3
"""Runs every test suite and prints one summary line: "N passed, M failed".

Suites: C++ (gtest), Python under headless FreeCAD (pytest), GUI under Xvfb
(each tests/gui/gui_test_*.py run by the real FreeCAD, reporting a JSON file).
Exit status 0 only when nothing failed.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FREECAD_LIB = "/usr/lib/freecad-python3/lib"


def run_cpp(tmp):
    report = Path(tmp) / "gtest.json"
    proc = subprocess.run(
        [str(ROOT / "build" / "tessella_tests"), f"--gtest_output=json:{report}"], cwd=ROOT
    )
    if not report.exists():
        return 0, 1
    data = json.loads(report.read_text())
    failed = int(data.get("failures", 0)) + int(data.get("errors", 0))
    total = int(data.get("tests", 0))
    if proc.returncode != 0 and failed == 0:
        failed = 1
    return total - failed, failed


def run_python(tmp):
    report = Path(tmp) / "pytest.xml"
    env = dict(os.environ, PYTHONPATH=f"{FREECAD_LIB}:{ROOT}")
    proc = subprocess.run(
        ["/usr/bin/python3", "-m", "pytest", "-q", "-p", "no:cacheprovider",
         f"--junitxml={report}", str(ROOT / "tests" / "python")],
        cwd=ROOT, env=env,
    )
    if not report.exists():
        return 0, 1
    suite = ET.parse(report).getroot()
    if suite.tag == "testsuites":
        suite = suite[0]
    total = int(suite.get("tests", 0))
    failed = int(suite.get("failures", 0)) + int(suite.get("errors", 0))
    skipped = int(suite.get("skipped", 0))
    if proc.returncode not in (0, 5) and failed == 0:
        failed = 1
    return total - failed - skipped, failed


def gui_env(tmp, **extra):
    """The environment of a GUI test's FreeCAD: its own user settings, data (Mod
    folder) and temp under `tmp` (HOME and the XDG folders too), so neither the
    user's preferences nor a copy of Tessella installed in their Mod folder
    (`make install`) is seen; the checkout is registered by the test itself."""
    home = Path(tmp) / "freecad-home"
    dirs = {"HOME": home, "XDG_CONFIG_HOME": home / ".config", "XDG_DATA_HOME": home / ".local/share",
            "XDG_CACHE_HOME": home / ".cache", "FREECAD_USER_HOME": home,
            "FREECAD_USER_DATA": home / "freecad-data", "FREECAD_USER_TEMP": home / "freecad-temp"}
    for d in dirs.values():
        d.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, **{k: str(v) for k, v in dirs.items()})
    env.update(TESSELLA_ROOT=str(ROOT), QTWEBENGINE_DISABLE_SANDBOX="1", **extra)
    return env


def run_gui(tmp):
    passed = failed = 0
    for script in sorted((ROOT / "tests" / "gui").glob("gui_test_*.py")):
        result = Path(tmp) / (script.stem + ".json")
        env = gui_env(tmp, TESSELLA_GUI_RESULT=str(result))
        print(f"GUI: {script.name}", flush=True)
        try:
            subprocess.run(["xvfb-run", "-a", "freecad", str(script)], cwd=ROOT, env=env,
                           timeout=600, stdin=subprocess.DEVNULL)
        except subprocess.TimeoutExpired:
            print(f"GUI: {script.name} timed out")
        if not result.exists():
            print(f"GUI: {script.name} wrote no result")
            failed += 1
            continue
        data = json.loads(result.read_text())
        for failure in data.get("failures", []):
            print(f"GUI FAILED: {failure}")
        passed += int(data.get("passed", 0))
        failed += int(data.get("failed", 0))
    return passed, failed


SUITES = {"cpp": run_cpp, "python": run_python, "gui": run_gui}


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--only", choices=sorted(SUITES), action="append")
    args = parser.parse_args()
    names = args.only or list(SUITES)
    total_passed = total_failed = 0
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            passed, failed = SUITES[name](tmp)
            lines.append(f"  {name}: {passed} passed, {failed} failed")
            total_passed += passed
            total_failed += failed
    print("\n".join(lines))
    print(f"{total_passed} passed, {total_failed} failed")
    return 0 if total_failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
