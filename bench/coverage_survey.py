"""Coverage of every method on every bundled example: the share of the face
left uncovered (gap) and covered twice or outside the trims (over), as the
pipeline measures them (summary gap_fraction / overlap_fraction), and the
panels' 3D area over the face area. A tiling method that breaks 0.1% is
refused by the pipeline: its line shows the refusal.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/coverage_survey.py [--divisions 12]

Parameters per face as in bench/result_hashes.py (size = sqrt(area) / divisions,
guides = iso-curves through the middle of the parameter range, walking_agent
and gradient_descent at 0.002 x the bounding-box diagonal).
"""

import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import result_hashes as rh  # noqa: E402  (imports FreeCAD before Part)

import freecad_workbench as tessella  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--divisions", type=float, default=rh.DIVISIONS)
    args = ap.parse_args()
    rh.DIVISIONS = args.divisions
    print("| example | method | panels | gap % | over % | 3D area / face | s | note |")
    print("|---|---|---|---|---|---|---|---|")
    for name, face in rh.example_faces():
        for method in rh.METHOD_NAMES:
            t0 = time.perf_counter()
            try:
                r = tessella.panelize(face, method=method, **rh.case_params(method, face))
            except (ValueError, RuntimeError) as exc:
                msg = str(exc).splitlines()[0][:110]
                print(f"| {name} | {method} | | | | | {time.perf_counter() - t0:.2f} | {msg} |")
                continue
            s = r.summary
            note = "warning" if s["coverage_warning"] else ""
            print(f"| {name} | {method} | {s['panel_count']} | {100 * s['gap_fraction']:.3f} | "
                  f"{100 * s['overlap_fraction']:.3f} | {s['model_area_ratio']:.4f} | "
                  f"{time.perf_counter() - t0:.2f} | {note} |", flush=True)


if __name__ == "__main__":
    main()
