# SPDX-License-Identifier: GPL-3.0-or-later
"""Add-on preferences, keyed by __package__ so they work as add-on and as extension."""

import bpy
from bpy.props import BoolProperty


class PolycubePreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    live_preview: BoolProperty(
        name="Show Iterations While Solving",
        description="In the viewport, show each kept iteration as soon as it is written",
        default=True)

    def draw(self, context):
        if native_error() is not None:
            from .unavailable import explain
            explain(self.layout.box())
        self.layout.prop(self, "live_preview")


_native_error = [None]


def set_native_error(message):
    _native_error[0] = message


def native_error():
    """Why the native module could not be imported, or None."""
    return _native_error[0]


def live_preview(context):
    # The package may run without being an enabled add-on (headless script): defaults then.
    addon = context.preferences.addons.get(__package__)
    return addon.preferences.live_preview if addon is not None else True
