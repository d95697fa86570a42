"""Registers every Tessella command with FreeCADGui (importing a command module
registers its commands) and lists them in toolbar order for InitGui.py."""

from . import analysis_commands, commands, fabrication_commands

#: Command names, in toolbar and menu order.
COMMANDS = commands.COMMANDS + analysis_commands.COMMANDS + fabrication_commands.COMMANDS

#: The menu and toolbar: Panelize / Analyse / Fabricate, separated.
MENU = (commands.COMMANDS + ["Separator"] + analysis_commands.COMMANDS + ["Separator"]
        + fabrication_commands.COMMANDS)
