# SPDX-License-Identifier: GPL-3.0-or-later
"""The label operators: Auto Label, Validate Labels and Label Colors.

Labels are read and written as labels.py says (docs/design.md section 3); every
operator is undoable and reports in one sentence per object.
"""

from time import perf_counter

import bpy
import numpy as np
from bpy.props import BoolProperty

from . import label_cache
from .background_call import BackgroundCall
from .face_selection import poll_mesh_to_select_in, select_faces_in_edit_mode
from .label_colours import colour_faces, colours_shown, hide_colours
from .label_source import automatic_labels, mark_automatic
from .labels import read_labels, write_face_maps, write_label_attribute
from .mesh_arrays import read_mesh_arrays
from .operators import PASS_THROUGH
from .redo_estimate import RedoEstimate
from .report import failure
from .settings import LabelSettings, label_options
from .validation import details, offending_faces, summary, validate

# Violations listed one by one in the info log; the rest are counted.
_DETAILS_SHOWN = 50


def _selected_meshes(context):
    """The selected mesh objects by name, each mesh once."""
    objects, meshes = [], set()
    for obj in sorted(context.selected_objects, key=lambda o: o.name):
        if obj.type == 'MESH' and obj.data.name not in meshes:
            objects.append(obj)
            meshes.add(obj.data.name)
    return objects


def _poll_object_mode_meshes(cls, context):
    if context.mode != 'OBJECT':
        cls.poll_message_set("Switch to Object Mode first")
        return False
    if not any(obj.type == 'MESH' for obj in context.selected_objects):
        cls.poll_message_set("Select one or more mesh objects")
        return False
    return True


class OBJECT_OT_polycube_auto_label(RedoEstimate, LabelSettings, bpy.types.Operator):
    """Label every face of the selected meshes automatically: the polycube_label attribute and, \
in Blender 3.x, face maps +X ... -Z"""
    bl_idname = "object.polycube_auto_label"
    bl_label = "Auto Label"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return _poll_object_mode_meshes(cls, context)

    def draw(self, context):
        self.layout.use_property_split = True
        for name in label_options(self):
            self.layout.prop(self, name)
        self.draw_estimate(self.layout)

    def execute(self, context):
        """Every object in turn, to the end (background mode, scripts, the redo panel)."""
        self._labelled = 0
        self.last_seconds = 0.0
        for obj, mesh in self._read(context):
            start = perf_counter()
            try:
                labels = automatic_labels(mesh, label_options(self))
            except ValueError as error:
                # An error, not a warning: scripts (headless --labels auto) see it as RuntimeError.
                self.report({'ERROR'}, failure(obj.name, "labelled", error))
                continue
            finally:
                self.last_seconds += perf_counter() - start
            self._write(obj, mesh, labels)
        return {'FINISHED'} if self._labelled else {'CANCELLED'}

    def invoke(self, context, event):
        """In the UI: the labeller on a worker thread, progress in the status bar, Esc stops."""
        if bpy.app.background:
            return self.execute(context)
        self._labelled = 0
        self._pending = [(obj.name, mesh) for obj, mesh in self._read(context)]
        if not self._pending:
            return {'CANCELLED'}
        self._total = len(self._pending)
        self.last_seconds = 0.0
        wm = context.window_manager
        wm.progress_begin(0, self._total)
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        self._next(context)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if event.type == 'ESC' and event.value == 'PRESS':
            left = [self._name] + [name for name, _ in self._pending]
            self.report({'WARNING'}, f"Auto Label stopped: {', '.join(repr(name) for name in left)} "
                                     f"kept {'its' if len(left) == 1 else 'their'} labels.")
            return self._end(context)
        if event.type != 'TIMER':
            return {'PASS_THROUGH'} if event.type in PASS_THROUGH else {'RUNNING_MODAL'}
        if not self._call.done:
            self._show_progress(context)
            return {'RUNNING_MODAL'}
        self.last_seconds += self._call.seconds
        obj = bpy.data.objects.get(self._name)
        if self._call.error is not None:
            self.report({'ERROR'}, failure(self._name, "labelled", self._call.error))
        elif obj is None or obj.type != 'MESH' or len(obj.data.polygons) != len(self._call.result):
            self.report({'WARNING'}, f"'{self._name}' was not labelled: it changed while it was being labelled.")
        else:
            self._write(obj, self._mesh, self._call.result)
        if not self._pending:
            return self._end(context)
        self._next(context)
        return {'RUNNING_MODAL'}

    def _read(self, context):
        """(object, MeshArrays) of each selected mesh that can be labelled."""
        for obj in _selected_meshes(context):
            try:
                yield obj, read_mesh_arrays(obj.data)
            except ValueError as error:
                self.report({'ERROR'}, failure(obj.name, "labelled", error))

    def _next(self, context):
        self._name, self._mesh = self._pending.pop(0)
        self._call = BackgroundCall(automatic_labels, self._mesh, label_options(self))
        self._show_progress(context)

    def _show_progress(self, context):
        done = self._total - len(self._pending) - 1
        context.window_manager.progress_update(done)
        context.workspace.status_text_set(
            f"Auto Label: '{self._name}' ({done + 1} of {self._total}), {self._call.seconds:.1f} s "
            f"(Esc to stop)")

    def _end(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)
        return {'FINISHED'} if self._labelled else {'CANCELLED'}

    def _write(self, obj, mesh, labels):
        """Write the labels to the object (main thread) and say how they validate."""
        write_label_attribute(obj.data, labels)
        label_cache.forget()  # the sidebar reads them afresh at its next draw
        mark_automatic(obj.data, labels)
        in_user_maps = write_face_maps(obj, labels) if hasattr(obj, "face_maps") else 0
        if colours_shown(obj.data):
            colour_faces(obj.data, labels)
        result = validate(obj, mesh, labels)
        for problem in result["orientation"]:
            self.report({'WARNING'}, f"'{obj.name}': {problem}.")
        self.report({'INFO'}, summary(obj.name, result))
        if in_user_maps:
            self.report({'INFO'}, f"'{obj.name}': {in_user_maps} faces stay in your own face maps; "
                                  f"the polycube_label attribute holds their labels.")
        self._labelled += 1


class OBJECT_OT_polycube_validate_labels(bpy.types.Operator):
    """Check the active mesh's labels against the polycube conditions; select the faces \
of every violation in Edit Mode"""
    bl_idname = "object.polycube_validate_labels"
    bl_label = "Validate Labels"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return poll_mesh_to_select_in(cls, context, context.active_object)

    def execute(self, context):
        obj = context.active_object
        was_editing = context.mode == 'EDIT_MESH'
        if was_editing:
            bpy.ops.object.mode_set(mode='OBJECT')  # the mesh data catches up with the edits
        try:
            mesh = read_mesh_arrays(obj.data)
            result = validate(obj, mesh, read_labels(obj).values)
        except ValueError as error:
            if was_editing:
                bpy.ops.object.mode_set(mode='EDIT')
            self.report({'ERROR'}, failure(obj.name, "validated", error))
            return {'CANCELLED'}
        for problem in result["orientation"]:
            self.report({'WARNING'}, f"'{obj.name}': {problem}.")
        if result["realisable"]:
            if was_editing:
                bpy.ops.object.mode_set(mode='EDIT')
            self.report({'WARNING'} if result["orientation"] else {'INFO'}, summary(obj.name, result))
            return {'FINISHED'}
        lines = details(result)
        for line in lines[:_DETAILS_SHOWN]:
            self.report({'INFO'}, f"'{obj.name}': {line}.")
        if len(lines) > _DETAILS_SHOWN:
            self.report({'INFO'}, f"'{obj.name}': {len(lines) - _DETAILS_SHOWN} more violations.")
        faces = offending_faces(result)
        select_faces_in_edit_mode(context, obj, faces)
        # Last, so that the status bar shows it.
        self.report({'WARNING'}, summary(obj.name, result, len(faces)))
        return {'FINISHED'}


class OBJECT_OT_polycube_label_colours(bpy.types.Operator):
    """Show the selected meshes' labels as face colors (the polycube_label_colour attribute), \
or hide them again"""
    bl_idname = "object.polycube_label_colours"
    bl_label = "Label Colors"
    bl_options = {'REGISTER', 'UNDO'}

    show: BoolProperty(
        name="Show", description="Show (or refresh) the label colors; off: remove them", default=True)

    @classmethod
    def poll(cls, context):
        return _poll_object_mode_meshes(cls, context)

    def execute(self, context):
        changed = 0
        for obj in _selected_meshes(context):
            if not self.show:
                hide_colours(obj.data)
                changed += 1
                continue
            try:
                colour_faces(obj.data, read_labels(obj).values)
            except ValueError as error:
                self.report({'WARNING'}, failure(obj.name, "coloured", error))
                continue
            changed += 1
        if self.show and changed:
            _show_attribute_colours(context)
        return {'FINISHED'} if changed else {'CANCELLED'}


def _show_attribute_colours(context):
    """Solid shading in this window's 3D views shows the active colour attribute."""
    for area in context.screen.areas if context.screen is not None else ():
        if area.type == 'VIEW_3D':
            area.spaces.active.shading.color_type = 'VERTEX'
