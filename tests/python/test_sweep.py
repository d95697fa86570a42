"""bench/sweep.py on a small folder: real runs in worker processes, the
outcomes counted per run (a hang is a timeout, a dying worker a crash, and the
sweep goes on with a fresh worker), the independent re-measure."""

import os
import shutil
import sys

import FreeCAD  # noqa: F401  (before Part)
import Part

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "bench"))
import sweep  # noqa: E402


def corpus(tmp_path):
    folder = tmp_path / "corpus"
    folder.mkdir()
    shutil.copy(os.path.join(REPO, "examples", "bezier_patch.brep"), folder)
    Part.makePlane(1000, 1000).exportBrep(str(folder / "plane.brep"))  # planar: not taken
    return folder


def test_jobs_take_the_non_planar_faces(tmp_path):
    folder = corpus(tmp_path)
    files = sweep.cad_files(str(folder))
    assert [os.path.basename(f) for f in files] == ["bezier_patch.brep", "plane.brep"]
    jobs, taken = sweep.list_jobs(files, ["iso_grid", "boundary_driven"], [6.0, 12.0], 0)
    assert taken == {files[0]: 1, files[1]: 0}
    assert len(jobs) == 4 and {j[2] for j in jobs} == {"iso_grid", "boundary_driven"}


def test_runs_are_measured_and_isolated(tmp_path):
    folder = corpus(tmp_path)
    path = str(folder / "bezier_patch.brep")
    jobs = [(path, 0, "iso_grid", 6.0), (path, 0, "walking_agent", 6.0),
            (path, 0, "iso_grid", 1e9),   # a size out of range: a clear error
            (path, 7, "iso_grid", 6.0)]   # no such face: an error of the sweep's own code
    rows = sweep.run_jobs(jobs, str(folder), lanes_count=2, timeout=120.0, remeasure_count=4)
    assert [r["status"] for r in rows] == ["ok", "ok", "error", "error"]
    ok = rows[0]
    assert ok["panels"] > 10 and ok["remeasured"] >= 1
    # Reported deviations are upper bounds within 1% of the dense re-measure.
    assert 0.99 <= ok["ratio_min"] <= ok["ratio_max"] <= 1.02, ok
    assert "size" in rows[2]["message"] and not rows[2].get("internal")
    assert rows[3].get("internal")


def test_a_hang_is_a_timeout_and_the_sweep_goes_on(tmp_path):
    folder = corpus(tmp_path)
    path = str(folder / "bezier_patch.brep")
    # A worker gets no time at all for the first job (it still imports FreeCAD):
    # that run is a timeout, the worker is replaced and the next run is ok.
    jobs = [(path, 0, "iso_grid", 6.0)]
    rows = sweep.run_jobs(jobs, str(folder), timeout=0.01, remeasure_count=0)
    assert rows[0]["status"] == "timeout"
    rows = sweep.run_jobs(jobs * 2, str(folder), timeout=120.0, remeasure_count=0)
    assert [r["status"] for r in rows] == ["ok", "ok"]


def test_a_dying_worker_is_a_crash(tmp_path):
    folder = corpus(tmp_path)
    w = sweep.Worker(0)
    w.proc.kill()  # what a segfault in the core looks like from the parent
    w.proc.wait()
    assert w.run([str(folder / "bezier_patch.brep"), 0, "iso_grid", 6.0], 10.0)["status"] == "crash"
