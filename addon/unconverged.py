# SPDX-License-Identifier: GPL-3.0-or-later
"""Select Unconverged Faces: where the last deformation stayed above the tolerance."""

import bpy

from .face_selection import poll_mesh_to_select_in, select_faces_in_edit_mode
from .report import load_report, report_faces

UNCONVERGED = "unconverged_faces"


def unconverged_count(report):
    """How many faces the run left above the tolerance; None if the solver does not say."""
    count = report.get(UNCONVERGED + "_count") if report is not None else None
    return int(count) if count is not None else None


class OBJECT_OT_polycube_select_unconverged(bpy.types.Operator):
    """Select, in Edit Mode, the faces the last deformation left above the tolerance"""
    bl_idname = "object.polycube_select_unconverged"
    bl_label = "Select Unconverged Faces"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        if not poll_mesh_to_select_in(cls, context, obj):
            return False
        if not unconverged_count(load_report(obj)):
            cls.poll_message_set("The active object's last deformation left no face above the tolerance")
            return False
        return True

    def execute(self, context):
        obj = context.active_object
        faces = report_faces(obj, UNCONVERGED)
        if context.mode == 'EDIT_MESH':
            bpy.ops.object.mode_set(mode='OBJECT')
        if len(faces) and faces.max() >= len(obj.data.polygons):
            self.report({'ERROR'}, f"'{obj.name}' has changed since it was deformed: deform it again.")
            return {'CANCELLED'}
        select_faces_in_edit_mode(context, obj, faces)
        report = load_report(obj)
        flipped = report.get("flipped_face_ids_count")
        among = f" ({flipped} of them flipped)" if flipped is not None else ""
        # The solver lists a limited number of faces; the count is exact.
        count = unconverged_count(report)
        listed = f"the {len(faces)} it lists of " if len(faces) < count else ""
        self.report({'INFO'}, f"'{obj.name}': selected {listed}{count} faces above the tolerance{among}.")
        return {'FINISHED'}
