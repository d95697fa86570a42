"""Tessella: panels, rods and nodes from freeform surfaces.

Console API (no document needed):

    import FreeCAD, Part
    import freecad_workbench as tessella
    r = tessella.panelize(face, method="iso_grid", size=1500.0)

Document objects (need FreeCAD):

    obj = tessella.make_panelization((doc_obj, "Face1"), method="equal_size_grid", size=2000.0)
"""

__version__ = "0.1.0"

from .api import METHODS, Cancelled, PanelizeResult, panelize  # noqa: F401,E402
from .plots import histograms  # noqa: F401,E402
from .boundary_driven import boundary_driven_stages  # noqa: F401,E402


def gui_progress(title="Tessella"):
    """A progress callback showing FreeCAD's progress dialog with a Cancel button
    (None without the GUI, so recorded macros replay headless)."""
    from .progress import gui_progress as _gp

    return _gp(title)


def make_panelization(*args, **kwargs):
    """Create a parametric Panelization object (see freecad_workbench.make)."""
    from .make import make_panelization as _make

    return _make(*args, **kwargs)


def make_curve_network(*args, **kwargs):
    """Show the traced curves of a boundary_driven Panelization (see freecad_workbench.make)."""
    from .make import make_curve_network as _make

    return _make(*args, **kwargs)
