"""The live preview of the Panelization task panel: a debounced re-run of the
panelization with the values shown, its rods drawn in the 3D view (a coarse
preview first when the result would be large) and a summary line.

The panelization runs on a worker thread (api.PreparedRun: the faces and
keywords are read from FreeCAD on the GUI thread first; the core releases
the GIL), so the GUI keeps turning while a large preview computes: a timer
collects the results, a newer change makes the running one stop at its next
progress report (its result is dropped), and "Stop preview" stops it.

Nothing here touches the document.
"""

import math
import threading
import time

import FreeCADGui as Gui

from .. import api

#: Debounce between the last change and the preview.
PREVIEW_DELAY_MS = 250
#: Above this many estimated panels a coarse preview (about COARSE_PANELS) comes first.
COARSE_ABOVE = 3000
COARSE_PANELS = 800
#: Samples per panel edge for the preview's deviation figure (the object uses 8).
PREVIEW_SAMPLES = 3


class Preview:
    """inputs() -> (face argument, method, keyword parameters) as shown;
    summary: the QLabel for the summary line; live: the "Live preview" check box."""

    def __init__(self, inputs, summary, live, stop_button=None):
        from PySide import QtCore

        self.inputs = inputs
        self.stop_button = stop_button
        if stop_button is not None:
            stop_button.setEnabled(False)
            stop_button.clicked.connect(self.stop_running)
        self._generation = 0  # the newest request; older results are dropped
        self._job = None  # (generation, worker box, start time) of the running one
        self._cancel = False
        self.poll = QtCore.QTimer()
        self.poll.setInterval(30)
        self.poll.timeout.connect(self._collect)
        self.summary = summary
        self.live = live
        self.node = None
        self.last_result = None
        self.last_error = None
        self.count = 0  # previews drawn (tests and the benchmark read it)
        self.seconds = 0.0
        self.timer = QtCore.QTimer()
        self.timer.setSingleShot(True)
        self.timer.setInterval(PREVIEW_DELAY_MS)
        self.timer.timeout.connect(lambda: self.update(wait=False))

    def schedule(self, *args):
        """Preview after the debounce (or remove it when live preview is off)."""
        if self.live.isChecked():
            self.timer.start()
        else:
            self.cancel()
            self.remove()

    def update(self, wait=True):
        """Panelize with the shown values and draw the rods; coarse first if large.

        The work runs on a worker thread; with `wait` (an explicit update: the
        tests, the benchmark) this returns once it is drawn, the events still
        processed meanwhile; without (the debounce timer) at once."""
        from ..selection import faces_of

        started = time.perf_counter()
        self._generation += 1
        generation = self._generation
        self._cancel = False
        try:
            face, method, params = self.inputs()
            runs = []
            size = params.get("size")
            if size and "u_count" not in params:
                area = sum(f.Area for f in faces_of(face, context="source"))
                estimate = area / (size * size)
                if estimate > COARSE_ABOVE:
                    coarse = dict(params, size=math.sqrt(area / COARSE_PANELS), samples=2)
                    runs.append((api.PreparedRun(face, method, coarse), True))
            # The preview measures with fewer samples than the final result.
            runs.append((api.PreparedRun(face, method, dict(params, samples=PREVIEW_SAMPLES)),
                         False))
        except Exception as exc:  # shown in the panel, never raised into the GUI
            self._show_error(exc)
            return
        box = {"results": [], "error": None, "done": False, "stage": "", "fraction": 0.0}

        def progress(fraction, stage):
            box["fraction"], box["stage"] = fraction, stage
            return generation == self._generation and not self._cancel

        def work():
            try:
                for run, coarse in runs:
                    box["results"].append((run.run(progress), coarse))
            except Exception as exc:  # noqa: BLE001  (handed to the GUI thread)
                box["error"] = exc
            box["done"] = True

        self._job = (generation, box, started)
        threading.Thread(target=work, name="TessellaPreview", daemon=True).start()
        if self.stop_button is not None:
            self.stop_button.setEnabled(True)
        self.poll.start()
        if wait:
            from PySide import QtGui

            self.timer.stop()  # no newer request while this one is awaited
            while not box["done"]:
                QtGui.QApplication.processEvents()
                time.sleep(0.002)
            self._collect()

    def busy(self):
        """Whether a preview is computing."""
        return self._job is not None

    def stop_running(self):
        """Stop the preview being computed ("Stop preview")."""
        if self._job is not None:
            self._cancel = True

    def cancel(self):
        """Drop whatever is computing (the panel closes, OK computes the result)."""
        self._generation += 1
        self._collect()

    def _collect(self):
        """Draw what the worker finished; the progress line while it runs."""
        job = self._job
        if job is None:
            self.poll.stop()
            return
        generation, box, started = job
        current = generation == self._generation
        while box["results"]:
            result, coarse = box["results"].pop(0)
            if current:
                self.draw(result, coarse=coarse)
                if not coarse:
                    self.last_result, self.last_error = result, None
                    self.seconds = time.perf_counter() - started
        if not box["done"]:
            if current and box["stage"]:
                text = self.summary.text().split(" (computing")[0]
                self.summary.setText(f"{text} (computing: {box['stage']}, "
                                     f"{100 * box['fraction']:.0f}%)")
            if current:
                return
        self._job = None
        self.poll.stop()
        if self.stop_button is not None:
            self.stop_button.setEnabled(False)
        if not current:
            return
        error = box["error"]
        if isinstance(error, api.Cancelled):
            self.last_result, self.last_error = None, "preview stopped"
            self.remove()
            self.summary.setText("Preview stopped (change a value or tick Live preview to run it again).")
        elif error is not None:
            self._show_error(error)

    def _show_error(self, exc):
        self.last_result, self.last_error = None, str(exc)
        self.remove()
        self.summary.setText(f"<span style='color:#b00020'>{exc}</span>")

    def draw(self, result, coarse=False):
        """Draw the rods of a result in the active 3D view; write the summary."""
        self.remove()
        try:
            from pivy import coin
        except ImportError:
            coin = None
        view = getattr(Gui.ActiveDocument, "ActiveView", None) if Gui.ActiveDocument else None
        if coin is not None and view is not None and hasattr(view, "getSceneGraph"):
            node = coin.SoSeparator()
            node.setName("TessellaPreview")
            color = coin.SoBaseColor()
            from . import preferences

            color.rgb = preferences.defaults()["preview_color"] if not coarse else (0.6, 0.6, 0.6)
            style = coin.SoDrawStyle()
            style.lineWidth = 2
            coords = coin.SoCoordinate3()
            # numpy to lists in C: a 130,000-panel preview draws in a few tens of ms.
            import numpy as np

            pts = np.asarray(result.vertices, dtype=float).tolist()
            coords.point.setValues(0, len(pts), pts)
            lines = coin.SoIndexedLineSet()
            rods = np.asarray(result.rods, dtype=np.int64).reshape(-1, 2)
            index = np.column_stack([rods, np.full(len(rods), -1)]).ravel().tolist()
            lines.coordIndex.setValues(0, len(index), index)
            for child in (color, style, coords, lines):
                node.addChild(child)
            view.getSceneGraph().addChild(node)
            self.node = node
        s = result.summary
        dev = s["panel_deviation"]["max"] if s["panel_deviation"]["count"] else 0.0
        prefix = "Coarse preview: " if coarse else ""
        self.summary.setText(
            f"{prefix}{s['panel_count']} panels, {s['rod_count']} rods, {s['node_count']} nodes, "
            f"max deviation {dev:.2f} mm, {s['irregular_count']} irregular")
        self.count += 1
        from PySide import QtGui

        QtGui.QApplication.processEvents()

    def remove(self):
        """Take the preview out of the 3D view."""
        node = self.node
        self.node = None
        if node is None or Gui.ActiveDocument is None:
            return
        view = getattr(Gui.ActiveDocument, "ActiveView", None)
        if view is not None and hasattr(view, "getSceneGraph"):
            graph = view.getSceneGraph()
            if graph.findChild(node) >= 0:
                graph.removeChild(node)

    def stop(self):
        self.timer.stop()
        self.cancel()
