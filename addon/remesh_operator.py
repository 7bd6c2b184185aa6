# SPDX-License-Identifier: GPL-3.0-or-later
"""Polycube Remesh: an all-quad copy of the object from its polycube, irregular
vertices only at the polycube's corners (and, on an open mesh, at the corners of
its boundaries laid along the grid); materials, smooth shading and UV maps
carried over from the surface under it."""

import bpy
import numpy as np

from . import polycube_native
from .mesh_arrays import corner_loops, new_mesh
from .polycube_shape import poll_polycube, polycube_of
from .report import failure
from .subdivide import carry_face_flags

REMESH_SUFFIX = " quads"


def mesh_area(mesh):
    areas = np.empty(len(mesh.polygons), dtype=np.float64)
    mesh.polygons.foreach_get("area", areas)
    return float(areas.sum())


def _carry_uv_maps(source, target, result):
    """Each UV map of the source, interpolated at every new vertex from the input
    face corners it lies between (a quad across a UV seam takes one side's UVs)."""
    loops = corner_loops(source)
    corners, weights = np.asarray(result["vertex_corners"]), np.asarray(result["vertex_weights"])
    for layer in source.uv_layers:
        flat = np.empty(2 * len(source.loops), dtype=np.float32)
        layer.data.foreach_get("uv", flat)
        per_corner = flat.reshape(-1, 2)[loops]
        per_vertex = np.einsum("vk,vkd->vd", weights, per_corner[corners])
        new = target.uv_layers.new(name=layer.name)
        if new is None:
            break
        new.data.foreach_set("uv", per_vertex[np.asarray(result["face_indices"])].astype(np.float32).ravel())
        if layer.active:
            target.uv_layers.active = new


def edge_length_for_count(mesh, positions, labels, target_faces, area):
    """The edge length whose remesh has about `target_faces` quads. A quad of side h
    covers h^2 of the surface, which gives a first h; the polycube's planes then snap
    to whole grid steps (thin gaps get at least one), so the count runs over by a few
    percent up to a sixth: one correction by the square root of the ratio, and the
    nearer of the two counts wins. The trials skip the relaxation, which moves
    vertices and keeps the count."""
    def count(h):
        trial = polycube_native.quad_remesh(mesh.vertices, mesh.face_indices, mesh.face_sizes, positions,
                                            labels, edge_length=h, relax_iterations=0)
        return len(trial["face_sizes"])
    first = (area / target_faces) ** 0.5
    first_count = count(first)
    if first_count in (0, target_faces):  # nothing to correct from (0: the module reports it)
        return first
    second = first * (first_count / target_faces) ** 0.5
    return second if abs(count(second) - target_faces) < abs(first_count - target_faces) else first


class OBJECT_OT_polycube_remesh(bpy.types.Operator):
    """A new all-quad object from the last deformation: a grid laid on the polycube's
    faces and carried back onto the surface"""
    bl_idname = "object.polycube_remesh"
    bl_label = "Polycube Remesh"
    bl_options = {'REGISTER', 'UNDO'}

    mode: bpy.props.EnumProperty(
        name="Size", default='FACES',
        items=(('FACES', "Target Faces", "About this many quads"),
               ('EDGE_LENGTH', "Target Edge Length", "Quads about this wide, in the object's units")))
    target_faces: bpy.props.IntProperty(name="Target Faces", default=5000, min=6, soft_max=200000)
    edge_length: bpy.props.FloatProperty(name="Edge Length", default=0.05, min=1e-6, soft_max=10.0,
                                         subtype='DISTANCE')
    relax: bpy.props.IntProperty(
        name="Relax", default=10, min=0, soft_max=50,
        description="Sweeps evening the vertices out on the surface where the grid carried back is "
                    "stretched (strips the polycube collapsed); 0: the grid as carried back")

    @classmethod
    def poll(cls, context):
        return poll_polycube(cls, context)

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "mode")
        layout.prop(self, "target_faces" if self.mode == 'FACES' else "edge_length")
        layout.prop(self, "relax")

    def execute(self, context):
        obj = context.active_object
        try:
            mesh, positions, labels = polycube_of(obj)
            h = (self.edge_length if self.mode == 'EDGE_LENGTH' else
                 edge_length_for_count(mesh, positions, labels, self.target_faces, mesh_area(obj.data)))
            result = polycube_native.quad_remesh(mesh.vertices, mesh.face_indices, mesh.face_sizes, positions,
                                                 labels, edge_length=h, relax_iterations=self.relax)
        except ValueError as error:
            self.report({'ERROR'}, failure(obj.name, "remeshed", error))
            return {'CANCELLED'}
        copy = self._new_object(context, obj, result)
        boundaries = (f"; {result['straightened_loops']} of {result['boundary_loops']} open boundaries laid "
                      f"along the grid" if result["boundary_loops"] else "")
        self.report({'INFO'}, f"'{copy.name}': {len(result['face_sizes'])} quads, "
                              f"{result['irregular_vertices']} irregular vertices (polycube corners){boundaries}.")
        return {'FINISHED'}

    def _new_object(self, context, obj, result):
        data = new_mesh(obj.name + REMESH_SUFFIX, result["vertices"], result["face_indices"], result["face_sizes"])
        carry_face_flags(obj.data, data, np.asarray(result["source_face"]))
        _carry_uv_maps(obj.data, data, result)
        copy = bpy.data.objects.new(data.name, data)
        for collection in obj.users_collection:
            collection.objects.link(copy)
        copy.matrix_world = obj.matrix_world
        for other in context.selected_objects:
            other.select_set(False)
        copy.select_set(True)
        context.view_layer.objects.active = copy
        return copy
