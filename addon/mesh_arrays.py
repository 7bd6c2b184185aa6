# SPDX-License-Identifier: GPL-3.0-or-later
"""A Blender mesh as the numpy arrays the solver takes, and back.

Everything goes through foreach_get/foreach_set: a Python loop per vertex or face
would dominate the run time on real models.
"""

from typing import NamedTuple

import bpy
import numpy as np


class MeshArrays(NamedTuple):
    vertices: np.ndarray      # (n, 3) float64
    face_indices: np.ndarray  # all face corners, face by face, int32
    face_sizes: np.ndarray    # corners per face, int32


def read_coordinates(collection, count):
    """(count, 3) float64 from anything with a `co` (vertices, shape-key points)."""
    flat = np.empty(count * 3, dtype=np.float32)
    collection.foreach_get("co", flat)
    return flat.reshape(count, 3).astype(np.float64)


def write_coordinates(collection, positions):
    collection.foreach_set("co", np.ascontiguousarray(positions, dtype=np.float32).ravel())


def read_mesh_arrays(mesh):
    """The solver's input from a mesh; ValueError with one sentence if it cannot be deformed."""
    vertex_count, face_count = len(mesh.vertices), len(mesh.polygons)
    if vertex_count == 0:
        raise ValueError("the mesh is empty")
    if face_count == 0:
        raise ValueError("the mesh has no faces, only vertices or edges")
    vertices = read_coordinates(mesh.vertices, vertex_count)
    bad = ~np.isfinite(vertices).all(axis=1)
    if bad.any():
        count = int(bad.sum())
        raise ValueError(f"{'a vertex has' if count == 1 else f'{count} vertices have'} "
                         f"NaN or infinite coordinates")

    face_sizes = np.empty(face_count, dtype=np.int32)
    mesh.polygons.foreach_get("loop_total", face_sizes)
    loop_starts = np.empty(face_count, dtype=np.int32)
    mesh.polygons.foreach_get("loop_start", loop_starts)
    loop_vertices = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", loop_vertices)
    # Blender before 3.6 does not promise that faces own consecutive loops in face
    # order; gather the corners face by face when they do not.
    ends = np.cumsum(face_sizes)
    if np.array_equal(loop_starts, ends - face_sizes) and ends[-1] == len(loop_vertices):
        face_indices = loop_vertices
    else:
        corner = np.arange(ends[-1]) - np.repeat(ends - face_sizes, face_sizes)
        face_indices = loop_vertices[np.repeat(loop_starts, face_sizes) + corner]

    areas = np.empty(face_count, dtype=np.float32)
    mesh.polygons.foreach_get("area", areas)
    if not (areas > 0).any():
        raise ValueError("all of its faces have zero area")
    return MeshArrays(vertices, face_indices, face_sizes)


def face_of_corner(mesh):
    """The face each loop (face corner) belongs to."""
    sizes = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("loop_total", sizes)
    faces = np.empty(len(mesh.loops), dtype=np.int64)
    faces[corner_loops(mesh)] = np.repeat(np.arange(len(sizes)), sizes)
    return faces


def corner_loops(mesh):
    """The loop of each face corner, corners face by face (read_mesh_arrays' order)."""
    sizes = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("loop_total", sizes)
    starts = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("loop_start", starts)
    corner = np.arange(sizes.sum()) - np.repeat(np.cumsum(sizes) - sizes, sizes)
    return np.repeat(starts, sizes) + corner


def new_mesh(name, vertices, face_indices, face_sizes):
    """A Blender mesh from solver-style arrays (used to bring in OFF files)."""
    mesh = bpy.data.meshes.new(name)
    face_sizes = np.asarray(face_sizes, dtype=np.int32)
    mesh.vertices.add(len(vertices))
    write_coordinates(mesh.vertices, vertices)
    mesh.loops.add(len(face_indices))
    mesh.loops.foreach_set("vertex_index", np.asarray(face_indices, dtype=np.int32))
    mesh.polygons.add(len(face_sizes))
    mesh.polygons.foreach_set("loop_start", (np.cumsum(face_sizes) - face_sizes).astype(np.int32))
    if not bpy.types.MeshPolygon.bl_rna.properties["loop_total"].is_readonly:
        # Blender < 4.0 stores sizes; later versions derive them from loop_start.
        mesh.polygons.foreach_set("loop_total", face_sizes)
    mesh.update(calc_edges=True)
    mesh.validate()
    return mesh
