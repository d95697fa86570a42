"""The live preview of the Panelization task panel: a debounced re-run of the
panelization with the values shown, its rods drawn in the 3D view (a coarse
preview first when the result would be large) and a summary line.

Nothing here touches the document.
"""

import math
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

    def __init__(self, inputs, summary, live):
        from PySide import QtCore

        self.inputs = inputs
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
        self.timer.timeout.connect(self.update)

    def schedule(self, *args):
        """Preview after the debounce (or remove it when live preview is off)."""
        if self.live.isChecked():
            self.timer.start()
        else:
            self.remove()

    def update(self):
        """Panelize with the shown values and draw the rods; coarse first if large."""
        from ..selection import faces_of

        started = time.perf_counter()
        try:
            face, method, params = self.inputs()
            size = params.get("size")
            if size and "u_count" not in params:
                area = sum(f.Area for f in faces_of(face, context="source"))
                estimate = area / (size * size)
                if estimate > COARSE_ABOVE:
                    coarse = dict(params, size=math.sqrt(area / COARSE_PANELS), samples=2)
                    self.draw(api.panelize_source(face, method=method, **coarse), coarse=True)
            # The preview measures with fewer samples than the final result.
            result = api.panelize_source(face, method=method, **dict(params, samples=PREVIEW_SAMPLES))
        except Exception as exc:  # shown in the panel, never raised into the GUI
            self.last_result, self.last_error = None, str(exc)
            self.remove()
            self.summary.setText(f"<span style='color:#b00020'>{exc}</span>")
            return
        self.last_result, self.last_error = result, None
        self.draw(result)
        self.seconds = time.perf_counter() - started

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
            pts = [tuple(map(float, p)) for p in result.vertices]
            coords.point.setValues(0, len(pts), pts)
            lines = coin.SoIndexedLineSet()
            index = []
            for a, b in result.rods:
                index += [int(a), int(b), -1]
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
