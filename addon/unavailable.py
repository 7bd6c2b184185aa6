# SPDX-License-Identifier: GPL-3.0-or-later
"""What the add-on shows when its native module cannot load (a Python or a system
it was not built for, a missing library): the sidebar tab and the preferences say
why, instead of the add-on failing to enable."""

import bpy

from . import preferences
from .sidebar import SidebarTab


def explain(layout):
    layout.label(text="The polycube solver cannot load:", icon='ERROR')
    for line in preferences.native_error().split(": "):
        layout.label(text=line.strip())
    layout.label(text="Install the zip built for this Blender's Python")
    layout.label(text="and Linux (make package), then restart Blender.")


class VIEW3D_PT_polycube_unavailable(SidebarTab, bpy.types.Panel):
    bl_label = "Polycube"

    def draw(self, context):
        explain(self.layout)
