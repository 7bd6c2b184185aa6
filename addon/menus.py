# SPDX-License-Identifier: GPL-3.0-or-later
"""Where the operators appear besides the sidebar: Object > Polycube in Object Mode,
Face > Polycube Labels and the face context menu in Edit Mode (F3 searches these
menus), and the label pie menu on Shift Alt L in Edit Mode."""

import bpy

from .label_assign import VIEW3D_MT_polycube_assign_label, VIEW3D_MT_polycube_label_pie

PIE_KEY = dict(type='L', value='PRESS', shift=True, alt=True)


class VIEW3D_MT_polycube_object(bpy.types.Menu):
    bl_label = "Polycube"
    bl_idname = "VIEW3D_MT_polycube_object"

    def draw(self, context):
        layout = self.layout
        layout.operator("object.polycube_deform", icon='MESH_CUBE')
        layout.separator()
        layout.operator("object.polycube_auto_label", icon='SHADERFX')
        layout.operator("object.polycube_validate_labels", icon='CHECKMARK')
        layout.operator("object.polycube_label_colours", text="Show Label Colors", icon='COLOR').show = True
        layout.operator("object.polycube_label_colours", text="Hide Label Colors").show = False
        layout.separator()
        layout.operator("object.polycube_select_unconverged")
        layout.separator()
        layout.operator("object.polycube_uv", icon='UV')
        layout.operator("object.polycube_remesh", icon='MESH_GRID')


class VIEW3D_MT_polycube_labels(bpy.types.Menu):
    """The label tools in Edit Mode."""
    bl_label = "Polycube Labels"
    bl_idname = "VIEW3D_MT_polycube_labels"

    def draw(self, context):
        layout = self.layout
        layout.menu(VIEW3D_MT_polycube_assign_label.bl_idname)
        layout.operator("wm.call_menu_pie", text="Label Pie Menu").name = VIEW3D_MT_polycube_label_pie.bl_idname
        layout.operator("object.polycube_validate_labels", icon='CHECKMARK')
        layout.operator("object.polycube_select_unconverged")


def _object_menu(self, context):
    self.layout.separator()
    self.layout.menu(VIEW3D_MT_polycube_object.bl_idname)


def _face_menu(self, context):
    self.layout.separator()
    self.layout.menu(VIEW3D_MT_polycube_labels.bl_idname)


_MENUS = (
    ("VIEW3D_MT_object", _object_menu),
    ("VIEW3D_MT_edit_mesh_faces", _face_menu),
    ("VIEW3D_MT_edit_mesh_context_menu", _face_menu),
)
_keymap_items = []


def register():
    for menu, draw in _MENUS:
        getattr(bpy.types, menu).append(draw)
    keyconfig = bpy.context.window_manager.keyconfigs.addon
    if keyconfig is not None:  # None in background mode
        keymap = keyconfig.keymaps.new(name="Mesh", space_type='EMPTY')
        item = keymap.keymap_items.new("wm.call_menu_pie", **PIE_KEY)
        item.properties.name = VIEW3D_MT_polycube_label_pie.bl_idname
        _keymap_items.append((keymap, item))


def unregister():
    for keymap, item in _keymap_items:
        keymap.keymap_items.remove(item)
    _keymap_items.clear()
    for menu, draw in _MENUS:
        getattr(bpy.types, menu).remove(draw)
