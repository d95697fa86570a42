"""Workshop output: schedules (CSV); DXF and JSON writers live next to them.

    from freecad_workbench.export import write_panel_schedule
    write_panel_schedule(result, "panels.csv")

Writers take a `PanelizeResult` (see freecad_workbench.api) and need no FreeCAD document.
"""

from .schedule_csv import (  # noqa: F401
    FAMILY_COLUMNS,
    NODE_COLUMNS,
    PANEL_COLUMNS,
    ROD_COLUMNS,
    panel_perimeters,
    write_family_schedule,
    write_node_schedule,
    write_panel_schedule,
    write_rod_schedule,
    write_schedules,
)

__all__ = [
    "FAMILY_COLUMNS",
    "NODE_COLUMNS",
    "PANEL_COLUMNS",
    "ROD_COLUMNS",
    "panel_perimeters",
    "write_family_schedule",
    "write_node_schedule",
    "write_panel_schedule",
    "write_rod_schedule",
    "write_schedules",
]
