# SPDX-License-Identifier: GPL-3.0-or-later
"""Assign Label in Edit Mode: the selected faces get +X ... -Z, or no label (Clear),
from the sidebar, the face menus or the label pie menu (Shift Alt L).

Written through `bmesh` (Edit Mode holds the mesh there) into the `polycube_label`
attribute, which wins over face maps (docs/design.md section 3). The first assignment
creates the attribute holding the labels the mesh had so far, so the other faces
keep theirs. In Blender 3.x the face maps follow, as Auto Label writes them, so that
the two stores never disagree (the face maps panel shows the same labels). Shown
label colors follow (cleared faces: their nearest axis, pale).
"""

import bmesh
import bpy
import numpy as np
from bpy.props import EnumProperty

from . import label_cache
from .label_colours import COLOUR_ATTRIBUTE, LABEL_COLOURS, NEAREST_COLOURS, display_colour, nearest_axes
from .labels import LABEL_ATTRIBUTE, read_labels, write_face_maps
from .polycube_native import LABEL_NAMES
from .report import failure

CLEAR = 'NONE'
LABEL_ITEMS = tuple((name, name, f"Faces turn to the {name} direction") for name in LABEL_NAMES) + (
    (CLEAR, "Clear", "No label: the faces take the axis nearest their normal"),)
# Byte colors in bmesh are the stored (sRGB) values: the palette as the screen shows it.
_SHOWN_COLOURS = [display_colour(colour) for colour in LABEL_COLOURS]
_SHOWN_NEAREST = [display_colour(colour) for colour in NEAREST_COLOURS]


def label_value(item):
    """The label value (-1..5) of a LABEL_ITEMS identifier."""
    return -1 if item == CLEAR else LABEL_NAMES.index(item)


class MESH_OT_polycube_assign_label(bpy.types.Operator):
    """Give the selected faces a polycube label (the polycube_label attribute), or clear it"""
    bl_idname = "mesh.polycube_assign_label"
    bl_label = "Assign Polycube Label"
    bl_options = {'REGISTER', 'UNDO'}

    label: EnumProperty(name="Label", description="The label the selected faces get",
                        items=LABEL_ITEMS, default=LABEL_NAMES[0])

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        if obj is None or obj.type != 'MESH' or context.mode != 'EDIT_MESH':
            cls.poll_message_set("Select faces of a mesh in Edit Mode")
            return False
        return True

    @classmethod
    def description(cls, context, properties):
        value = label_value(properties.label)
        if value < 0:
            return "Clear the selected faces' polycube label: they take the axis nearest their normal"
        return f"Label the selected faces {LABEL_NAMES[value]}: they turn to that direction"

    def execute(self, context):
        value = label_value(self.label)
        faces = 0
        for obj in context.objects_in_mode_unique_data or (context.active_object,):
            try:
                faces += _assign(obj, value)
            except ValueError as error:
                self.report({'ERROR'}, failure(obj.name, "labelled", error))
                return {'CANCELLED'}
        label_cache.forget()  # an update of the depsgraph would, but need not come before a redraw
        if not faces:
            self.report({'WARNING'}, "Select the faces to label first.")
            return {'CANCELLED'}
        what = "Cleared the label of" if value < 0 else f"Labelled {LABEL_NAMES[value]}"
        self.report({'INFO'}, f"{what} {faces} face{'s' if faces != 1 else ''}.")
        return {'FINISHED'}


def _assign(obj, value):
    """Label the object's selected faces; how many there were."""
    mesh = obj.data
    stored = read_labels(obj)  # before any layer exists: what the faces hold so far
    bm = bmesh.from_edit_mesh(mesh)
    if not any(face.select for face in bm.faces):
        return 0
    layer = bm.faces.layers.int.get(LABEL_ATTRIBUTE)
    if layer is None:
        layer = bm.faces.layers.int.new(LABEL_ATTRIBUTE)  # invalidates earlier face references
        for face, label in zip(bm.faces, stored.values.tolist()):
            face[layer] = label
    selected = [face for face in bm.faces if face.select]
    for face in selected:
        face[layer] = value
    colours = bm.loops.layers.color.get(COLOUR_ATTRIBUTE)
    if colours is not None:
        shown = [_SHOWN_COLOURS[value]] * len(selected) if value >= 0 else \
            [_SHOWN_NEAREST[axis] for axis in nearest_axes([face.normal for face in selected])]
        for face, colour in zip(selected, shown):
            for loop in face.loops:
                loop[colours] = colour
    if hasattr(obj, "face_maps"):
        write_face_maps(obj, np.fromiter((face[layer] for face in bm.faces), dtype=np.int32, count=len(bm.faces)))
    bmesh.update_edit_mesh(mesh, loop_triangles=False, destructive=False)
    return len(selected)


def draw_label_buttons(layout):
    """+X ... -Z and Clear as a grid of buttons (sidebar and menus)."""
    grid = layout.grid_flow(row_major=True, columns=2, even_columns=True, align=True)
    for name in LABEL_NAMES:
        grid.operator(MESH_OT_polycube_assign_label.bl_idname, text=name).label = name
    layout.operator(MESH_OT_polycube_assign_label.bl_idname, text="Clear Label", icon='X').label = CLEAR


class VIEW3D_MT_polycube_assign_label(bpy.types.Menu):
    bl_label = "Assign Polycube Label"
    bl_idname = "VIEW3D_MT_polycube_assign_label"

    def draw(self, context):
        layout = self.layout
        for name in LABEL_NAMES:
            layout.operator(MESH_OT_polycube_assign_label.bl_idname, text=name).label = name
        layout.separator()
        layout.operator(MESH_OT_polycube_assign_label.bl_idname, text="Clear Label").label = CLEAR


# Pie slots in Blender's order: W, E, S, N, NW, NE, SW, SE. Each axis's two sides
# face each other across the pie.
_PIE = ("-X", "+X", "-Z", "+Z", "-Y", "+Y", CLEAR)


class VIEW3D_MT_polycube_label_pie(bpy.types.Menu):
    bl_label = "Polycube Label"
    bl_idname = "VIEW3D_MT_polycube_label_pie"

    def draw(self, context):
        pie = self.layout.menu_pie()
        for item in _PIE:
            text = "Clear Label" if item == CLEAR else item
            pie.operator(MESH_OT_polycube_assign_label.bl_idname, text=text,
                         icon='X' if item == CLEAR else 'NONE').label = item
        pie.operator("object.polycube_validate_labels", text="Validate Labels", icon='CHECKMARK')
