# SPDX-License-Identifier: GPL-3.0-or-later
"""Polycube: deform meshes into their polycube, one shape key per solver iteration.

Blender 3.x reads `bl_info`; Blender 4.2+ reads `blender_manifest.toml` beside this
file. Everything inside is imported relatively, so the package works under either
name (`polycube` or `bl_ext.<repository>.polycube`).
"""

bl_info = {
    "name": "Polycube",
    "author": "polycube developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Polycube",
    "description": "Deform meshes into their polycube, a shape key per iteration",
    "category": "Mesh",
    # Sections of the README the package carries; register() makes them file:// addresses.
    "doc_url": "README.md#blender-add-on",
    "tracker_url": "README.md#reporting-problems",
}

import os

import bpy

from . import help_links, preferences

try:
    from . import polycube_native  # noqa: F401 (the rest of the add-on imports it)
except ImportError as error:
    # The add-on still enables, and says why in its tab and its preferences.
    preferences.set_native_error(str(error))

if preferences.native_error() is None:
    from . import label_cache, menus, panel, scrub, settings
    from .label_assign import (
        MESH_OT_polycube_assign_label, VIEW3D_MT_polycube_assign_label, VIEW3D_MT_polycube_label_pie)
    from .label_operators import (
        OBJECT_OT_polycube_auto_label, OBJECT_OT_polycube_label_colours, OBJECT_OT_polycube_validate_labels)
    from .operators import OBJECT_OT_polycube_deform
    from .remesh_operator import OBJECT_OT_polycube_remesh
    from .unconverged import OBJECT_OT_polycube_select_unconverged
    from .uv_operator import OBJECT_OT_polycube_uv

    _classes = (
        preferences.PolycubePreferences,
        settings.PolycubeSceneSettings,
        OBJECT_OT_polycube_deform,
        OBJECT_OT_polycube_auto_label,
        OBJECT_OT_polycube_validate_labels,
        OBJECT_OT_polycube_label_colours,
        OBJECT_OT_polycube_select_unconverged,
        OBJECT_OT_polycube_uv,
        OBJECT_OT_polycube_remesh,
        MESH_OT_polycube_assign_label,
        VIEW3D_MT_polycube_assign_label,
        VIEW3D_MT_polycube_label_pie,
        menus.VIEW3D_MT_polycube_object,
        menus.VIEW3D_MT_polycube_labels,
    ) + panel.CLASSES
    _modules = (settings, scrub, label_cache, menus)  # register() in this order
else:
    from .unavailable import VIEW3D_PT_polycube_unavailable

    _classes = (preferences.PolycubePreferences, VIEW3D_PT_polycube_unavailable)
    _modules = ()


def register():
    folder = os.path.dirname(os.path.realpath(__file__))  # a source checkout's link: its README
    help_links.resolve(bl_info, folder)
    help_links.resolve_in_addon_list(__name__, folder)
    for cls in _classes:
        bpy.utils.register_class(cls)
    for module in _modules:
        module.register()


def unregister():
    for module in reversed(_modules):
        module.unregister()
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
