"""Tessella preferences (Edit > Preferences > Tessella) and their defaults.

Stored under User parameter:BaseApp/Preferences/Mod/Tessella; the page is
resources/ui/preferences.ui (FreeCAD's Pref* widgets write the values).
"""

import os

import FreeCAD

PARAM_PATH = "User parameter:BaseApp/Preferences/Mod/Tessella"
UI_FILE = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                       "resources", "ui", "preferences.ui")

#: Order of the method combo box on the page (stored as its index, so it only
#: grows at the end; a test checks it names every declared method).
METHOD_ORDER = ("iso_grid", "equal_size_grid", "boundary_driven", "walking_agent",
                "gradient_descent", "relaxed_grid", "guide_line_scaling", "two_guide_lines",
                "guide_line_diamond", "curvature_lines", "chebyshev_net")


def defaults():
    """The user's defaults for new panelizations (built-in values when unset)."""
    from ..methods import METHODS

    shared = METHODS[METHOD_ORDER[0]].params  # built-in defaults: the declarations'
    p = FreeCAD.ParamGet(PARAM_PATH)
    index = p.GetInt("DefaultMethod", 0)
    return {
        "method": METHOD_ORDER[index] if 0 <= index < len(METHOD_ORDER) else METHOD_ORDER[0],
        "panels_across": max(1, p.GetInt("PanelsAcross", 8)),
        "size": p.GetFloat("DefaultSize", 0.0),  # 0: from the face (PanelsAcross)
        "sliver_fraction": p.GetFloat("SliverFraction", shared["sliver_fraction"].default),
        "min_angle": p.GetFloat("MinAngle", shared["min_angle"].default),
        "max_panels": p.GetInt("MaxPanels", shared["max_panels"].default),
        "max_deviation": p.GetFloat("DefaultDeviation", 0.0),  # 0: the method's default
        "panel_id_format": valid_id_format(p.GetString("PanelIdFormat", "P-{:04d}")),
        # FreeCAD stores colours as 0xRRGGBBAA.
        "preview_color": _rgb(p.GetUnsigned("PreviewColor", 0xF2730DFF)),
    }


def _rgb(packed):
    return tuple(((packed >> shift) & 0xFF) / 255.0 for shift in (24, 16, 8))


def valid_id_format(fmt, fallback="P-{:04d}"):
    """The format if it turns a panel number into text, else the fallback."""
    try:
        text = fmt.format(1)
    except (IndexError, KeyError, ValueError):
        return fallback
    return fmt if text and text != fmt.format(2) else fallback


def register():
    """Add the page to Edit > Preferences (once per session)."""
    import FreeCADGui as Gui

    # The page's icon is looked up as "preferences-tessella" in the icon paths.
    icons = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))), "resources", "icons")
    if os.path.isdir(icons):
        Gui.addIconPath(icons)
    if os.path.isfile(UI_FILE):
        Gui.addPreferencePage(UI_FILE, "Tessella")
