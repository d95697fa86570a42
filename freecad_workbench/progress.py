"""Progress for long operations: a cancellable dialog in the GUI, nothing headless.

    obj = tessella.make_panelization(sel, size=200.0, progress=tessella.gui_progress())

The callback receives (fraction, stage) from the core about every 50 ms and
returns False once the user pressed Cancel; the core then raises Cancelled and
nothing is created.
"""

import FreeCAD


class GuiProgress:
    """Callable progress sink backed by a QProgressDialog that appears only for
    operations longer than half a second."""

    def __init__(self, title="Tessella"):
        from PySide import QtCore, QtGui
        import FreeCADGui as Gui

        self.dialog = QtGui.QProgressDialog(title, "Cancel", 0, 1000, Gui.getMainWindow())
        self.dialog.setWindowTitle(title)
        self.dialog.setObjectName("TessellaProgress")
        self.dialog.setWindowModality(QtCore.Qt.WindowModal)
        self.dialog.setMinimumDuration(500)
        self.dialog.setAutoClose(False)
        self.dialog.setAutoReset(False)
        self.dialog.setValue(0)
        self.calls = 0

    def __call__(self, fraction, stage):
        from PySide import QtGui

        self.calls += 1
        self.dialog.setLabelText(str(stage).capitalize() + " ...")
        self.dialog.setValue(max(0, min(999, int(fraction * 1000))))
        QtGui.QApplication.processEvents()
        return not self.dialog.wasCanceled()

    def cancel(self):
        """As if the user pressed Cancel (tests)."""
        self.dialog.cancel()

    def close(self):
        self.dialog.reset()
        self.dialog.close()


def gui_progress(title="Tessella"):
    if not FreeCAD.GuiUp:
        return None
    return GuiProgress(title)
