"""Metrics on several threads through the console API: the same arrays bit for
bit on 1 and 2 threads (TESSELLA_THREADS), and the cost figures in the summary."""

import numpy as np

import freecad_workbench as tessella


def _run(face, threads, monkeypatch):
    monkeypatch.setenv("TESSELLA_THREADS", str(threads))
    return tessella.panelize(face, method="iso_grid", size=1200.0)


def test_one_and_two_threads_give_identical_results(freeform_face, monkeypatch):
    a = _run(freeform_face, 1, monkeypatch)
    b = _run(freeform_face, 2, monkeypatch)
    assert a.summary["metrics_threads"] == 1
    assert b.summary["metrics_threads"] == 2
    assert a.panels == b.panels
    assert np.array_equal(a.vertices, b.vertices)
    for key in a.metrics:
        assert np.array_equal(a.metrics[key], b.metrics[key], equal_nan=True), key


def test_summary_reports_the_cost(freeform_face, monkeypatch):
    monkeypatch.delenv("TESSELLA_THREADS", raising=False)
    r = tessella.panelize(freeform_face, method="iso_grid", size=1200.0)
    s = r.summary
    assert s["metrics_threads"] >= 1  # every core (hardware_concurrency)
    assert s["global_projections"] == 0  # Newton (or its local retry) found every foot point
    assert 0 < s["metrics_seconds"] <= s["pipeline_seconds"]
    assert 0 < s["core_seconds"] <= s["pipeline_seconds"]
