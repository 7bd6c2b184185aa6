# SPDX-License-Identifier: GPL-3.0-or-later
"""A Workbench render of objects as they came in (left) beside their polycube (right).

Faces are coloured by label. Rendering happens in a scene of its own, with copies
of the objects, which is removed again: the user's scenes are not touched.
"""

import bpy
import numpy as np
from mathutils import Matrix, Vector

from .label_colours import colour_faces
from .labels import read_labels
from .mesh_arrays import read_coordinates, read_mesh_arrays
from .polycube_native import nearest_labels

_VIEW_FROM = Vector((0.6, -1.0, 0.7)).normalized()   # front, right and above


def render_preview(objects, filepath, resolution=(1600, 800)):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    scene = bpy.data.scenes.new("Polycube preview")
    copies = []  # (input, polycube) per object
    try:
        for obj in objects:
            labels = _resolved_labels(obj)
            before = _copy(scene, obj, obj.data.copy(), labels)
            before.shape_key_clear()  # the copied mesh brought the shape keys along
            after = _copy(scene, obj, bpy.data.meshes.new_from_object(obj.evaluated_get(depsgraph)), labels)
            copies.append((before, after))
        camera = _arrange(scene, copies, resolution[0] / resolution[1])
        _render(scene, camera, filepath, resolution)
    finally:
        for obj in list(scene.objects):
            data = obj.data
            bpy.data.objects.remove(obj)
            if isinstance(data, bpy.types.Mesh):
                bpy.data.meshes.remove(data)
            elif isinstance(data, bpy.types.Camera):
                bpy.data.cameras.remove(data)
        if scene.world is not None:
            bpy.data.worlds.remove(scene.world)
        bpy.data.scenes.remove(scene)


def _resolved_labels(obj):
    values = read_labels(obj).values
    if (values < 0).any():
        values = np.where(values < 0, nearest_labels(*read_mesh_arrays(obj.data)), values)
    return values


def _copy(scene, obj, mesh, labels):
    copy = bpy.data.objects.new(obj.name + " preview", mesh)
    copy.matrix_world = obj.matrix_world
    scene.collection.objects.link(copy)
    if len(mesh.polygons) == len(labels):
        colour_faces(mesh, labels)
    return copy


def _world_points(objects):
    return np.concatenate([
        read_coordinates(o.data.vertices, len(o.data.vertices)) @ np.array(o.matrix_world)[:3, :3].T
        + np.array(o.matrix_world)[:3, 3] for o in objects])


def _arrange(scene, copies, aspect):
    """Inputs left of the polycubes, seen from _VIEW_FROM by an orthographic camera."""
    rotation = (-_VIEW_FROM).to_track_quat('-Z', 'Y')
    right = np.array(rotation @ Vector((1, 0, 0)))
    up = np.array(rotation @ Vector((0, 1, 0)))
    groups = [[pair[0] for pair in copies], [pair[1] for pair in copies]]
    points = [_world_points(group) for group in groups]
    widths = [np.ptp(p @ right) for p in points]
    gap = 0.15 * max(widths)
    for side, group, group_points, width in zip((-1, 1), groups, points, widths):
        centre = (group_points.min(axis=0) + group_points.max(axis=0)) / 2
        shift = side * (width + gap) / 2 * right - centre
        for obj in group:
            obj.matrix_world = Matrix.Translation(Vector(shift)) @ obj.matrix_world
    placed = _world_points(groups[0] + groups[1])
    x, y = placed @ right, placed @ up
    size = np.ptp(placed, axis=0).max()
    camera_data = bpy.data.cameras.new("Polycube preview camera")
    camera_data.type = 'ORTHO'
    camera_data.ortho_scale = 1.08 * max(np.ptp(x), np.ptp(y) * aspect)
    camera_data.clip_end = 10 * size
    camera = bpy.data.objects.new("Polycube preview camera", camera_data)
    centre = right * (x.min() + x.max()) / 2 + up * (y.min() + y.max()) / 2
    depth = placed @ np.array(_VIEW_FROM)
    camera.location = Vector(centre) + _VIEW_FROM * float(depth.max() + size)
    camera.rotation_euler = rotation.to_euler()
    scene.collection.objects.link(camera)
    return camera


def _render(scene, camera, filepath, resolution):
    scene.camera = camera
    scene.render.engine = 'BLENDER_WORKBENCH'
    scene.render.resolution_x, scene.render.resolution_y = resolution
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = 'PNG'
    scene.render.filepath = filepath
    scene.view_settings.view_transform = 'Standard'
    scene.display.shading.light = 'STUDIO'
    scene.display.shading.color_type = 'VERTEX'
    scene.display.shading.show_cavity = True
    scene.world = bpy.data.worlds.new("Polycube preview")
    scene.world.color = (1.0, 1.0, 1.0)
    bpy.ops.render.render(write_still=True, scene=scene.name)
