"""Tessella: panels, rods and nodes from freeform surfaces.

Console API (no document needed):

    import FreeCAD, Part
    import freecad_workbench as tessella
    r = tessella.panelize(face, method="iso_grid", size=1500.0)
    r = tessella.panelize_faces(shell, method="iso_grid", size=1500.0)  # several faces

Document objects (need FreeCAD):

    obj = tessella.make_panelization((doc_obj, "Face1"), method="equal_size_grid", size=2000.0)
"""

__version__ = "0.1.0"

from .api import METHODS, Cancelled, PanelizeResult, panelize, panelize_faces  # noqa: F401,E402
from .plots import histograms  # noqa: F401,E402
from .boundary_driven import boundary_driven_stages  # noqa: F401,E402
from .families import PanelFamilies, panel_families  # noqa: F401,E402
from .panel_classes import PanelClasses, panel_classes  # noqa: F401,E402
from .family_regularization import regularize_families  # noqa: F401,E402
from .planarization import planarize  # noqa: F401,E402


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


from .fabrication import (  # noqa: F401,E402
    FlatPanel, FlatPatch, NestLayout, flatten, nest, smallest_sheet, unfold)


def export_dxf(*args, **kwargs):
    """Write flat panels (optionally nested) to a DXF file (see freecad_workbench.export.dxf)."""
    from .export.dxf import export_dxf as _export

    return _export(*args, **kwargs)


def export_svg(*args, **kwargs):
    """Write flat panels (optionally nested) to an SVG file (see freecad_workbench.export.svg)."""
    from .export.svg import export_svg as _export

    return _export(*args, **kwargs)

from .members import (  # noqa: F401,E402
    buildability,
    cut_list,
    freegrid_planarity,
    node_frames,
    node_types,
    panel_types,
    rod_data,
)


def make_unfold(*args, **kwargs):
    """Create a parametric Unfold object of a Panelization (see freecad_workbench.make_fabrication)."""
    from .make_fabrication import make_unfold as _make

    return _make(*args, **kwargs)


def rod_solids(*args, **kwargs):
    """Rods as solids with a profile (see freecad_workbench.solids; needs FreeCAD)."""
    from .solids import rod_solids as _f

    return _f(*args, **kwargs)


def hub_solids(*args, **kwargs):
    """Simple cylindrical hubs along the node axes (see freecad_workbench.solids)."""
    from .solids import hub_solids as _f

    return _f(*args, **kwargs)


def make_schedules(*args, **kwargs):
    """Panel, rod and node schedules as Spreadsheet objects (see freecad_workbench.spreadsheets)."""
    from .spreadsheets import make_schedules as _f

    return _f(*args, **kwargs)


def panel_solids(*args, **kwargs):
    """Panels with a thickness, offset along the node normals (see freecad_workbench.solids)."""
    from .solids import panel_solids as _f

    return _f(*args, **kwargs)


def export_unfold(*args, **kwargs):
    """Write an Unfold object's panels to DXF or SVG (see freecad_workbench.make_fabrication)."""
    from .make_fabrication import export_unfold as _f

    return _f(*args, **kwargs)


def _connect_gui():
    """In a FreeCAD GUI session, import the GUI package: it registers the hook
    through which restored features get their view providers (features never
    import the GUI). Headless, nothing GUI is imported."""
    import sys

    app = sys.modules.get("FreeCAD")
    if app is not None and getattr(app, "GuiUp", False):
        from . import gui  # noqa: F401


_connect_gui()
