# SPDX-License-Identifier: GPL-3.0-or-later
"""Polycube UV: a UV map from the object's polycube, one island per chart."""

import bpy
import numpy as np

from . import polycube_native
from .mesh_arrays import corner_loops
from .polycube_shape import poll_polycube, polycube_of
from .report import failure

UV_MAP_NAME = "Polycube"
MERGE_SLACK = 0.01  # the rise of angle and area distortion a merge may cost


def write_uv_map(mesh, uvs, name=UV_MAP_NAME):
    """Corner UVs (face by face, as read_mesh_arrays orders corners) into the UV map
    `name`, made (or refilled) and made active; the user's other UV maps are kept."""
    layer = mesh.uv_layers.get(name) or mesh.uv_layers.new(name=name)
    if layer is None:
        raise ValueError("the mesh has as many UV maps as Blender allows; remove one")
    per_loop = np.empty((len(mesh.loops), 2), dtype=np.float32)
    per_loop[corner_loops(mesh)] = uvs
    layer.data.foreach_set("uv", per_loop.ravel())
    mesh.uv_layers.active = layer
    return layer


class OBJECT_OT_polycube_uv(bpy.types.Operator):
    """UV map "Polycube" from the last deformation: every flat chart of the polycube one
    island, with the polycube's own distortion, packed at one texel density"""
    bl_idname = "object.polycube_uv"
    bl_label = "Polycube UV"
    bl_options = {'REGISTER', 'UNDO'}

    padding: bpy.props.FloatProperty(
        name="Padding", default=0.01, min=0.0, max=0.2,
        description="Gap between islands, relative to the square root of their area")

    relax: bpy.props.BoolProperty(
        name="Conformal", default=False,
        description="Re-solve each island to keep the mesh's angles (least-squares conformal); "
                    "the polycube still decides islands and seams")

    merge: bpy.props.BoolProperty(
        name="Merge Islands", default=False,
        description="Conformal, and neighbouring islands merged where they unfold together "
                    "(angle and area distortion each rise by at most 0.01): fewer islands, shorter seams")

    @classmethod
    def poll(cls, context):
        return poll_polycube(cls, context)

    def execute(self, context):
        obj = context.active_object
        try:
            mesh, positions, labels = polycube_of(obj)
            result = polycube_native.polycube_uv(mesh.vertices, mesh.face_indices, mesh.face_sizes, positions,
                                                 labels, padding=self.padding, relax=self.relax,
                                                 merge=MERGE_SLACK if self.merge else -1.0)
            write_uv_map(obj.data, result["uvs"])
        except ValueError as error:
            self.report({'ERROR'}, failure(obj.name, "given polycube UVs", error))
            return {'CANCELLED'}
        figures = polycube_native.uv_figures(mesh.vertices, mesh.face_indices, mesh.face_sizes, result["uvs"])
        self.report({'INFO'}, f"'{obj.name}': UV map '{UV_MAP_NAME}', {result['islands']} islands, "
                              f"angle distortion {figures['angle_distortion']:.3f}.")
        return {'FINISHED'}
