"""The deform operator's "subdivide before" option in Blender: it works on a
new object `<name> polycube` (4^k faces, labels carried from each parent face),
leaving the user's object, its vertex count and its shape keys alone."""

import os
import sys

import bpy
from mathutils import Vector
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    add_face_maps, deform, deform_error, enable_addon, key_names, nearest_axis_labels, report,
    run_tests, vertices)

polycube = enable_addon()
NAMES = polycube.polycube_native.LABEL_NAMES


def _labelled_cube():
    bpy.ops.mesh.primitive_cube_add()
    cube = bpy.context.active_object
    add_face_maps(cube, nearest_axis_labels(cube), NAMES)
    return cube


def _ico_sphere():
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=1.0)
    ico = bpy.context.active_object
    ico.name = "Ico"
    return ico


def _labels(obj):
    values = np.empty(len(obj.data.polygons), dtype=np.int32)
    obj.data.attributes["polycube_label"].data.foreach_get("value", values)
    return values


def _with_shape_keys(obj):
    obj.shape_key_add(name="Basis", from_mix=False)
    bulge = obj.shape_key_add(name="Bulge", from_mix=False)
    bulge.data.foreach_set("co", (vertices(obj) * 1.5).astype(np.float32).ravel())
    bulge.value = 0.25
    return vertices(obj)


def test_quads_subdivided_into_a_copy_with_4_to_the_k_faces():
    cube = _labelled_cube()
    cube.location = (2, 0, 0)
    material = bpy.data.materials.new("Paint")
    cube.data.materials.append(material)
    before = _with_shape_keys(cube)
    assert deform(cube, iterations=50, subdivide=True, subdivide_levels=2,
                  subdivide_scheme='BILINEAR') == {'FINISHED'}

    copy = bpy.data.objects["Cube polycube"]
    assert len(copy.data.polygons) == 6 * 4 ** 2
    # Every child face has its parent's label: 16 faces per side of the cube.
    assert np.bincount(_labels(copy), minlength=6).tolist() == [16] * 6
    assert report(copy)["subdivided_from"] == "Cube" and report(copy)["converged"]
    assert report(copy)["label_source"] == "face maps, subdivided (bilinear x2)"
    assert copy.data.materials[0] == material
    # Beside the cube (at x = 2), not on top of it: along x, past its shown width.
    x, y, z = copy.matrix_world.translation
    shown_right = max((cube.matrix_world @ Vector(corner)).x for corner in cube.bound_box)
    assert (y, z) == (0, 0) and x - 1 > shown_right + 0.25, (x, shown_right)
    # Bilinear keeps the shape: every vertex on the cube's surface.
    assert np.abs(np.abs(vertices(copy)).max(axis=1) - 1).max() < 1e-6

    assert len(cube.data.vertices) == 8 and np.array_equal(vertices(cube), before)
    assert key_names(cube) == ["Basis", "Bulge"]
    assert abs(cube.data.shape_keys.key_blocks["Bulge"].value - 0.25) < 1e-6
    assert report(cube) is None
    assert copy.select_get() and not cube.select_get()
    assert bpy.context.view_layer.objects.active == copy


def test_triangles_with_loop_and_automatic_labels_become_a_polycube():
    ico = _ico_sphere()
    before = _with_shape_keys(ico)
    faces = len(ico.data.polygons)
    assert deform(ico, iterations=200, label_source='AUTO', subdivide=True, subdivide_levels=1,
                  subdivide_scheme='LOOP') == {'FINISHED'}
    copy = bpy.data.objects["Ico polycube"]
    assert len(copy.data.polygons) == 4 * faces
    result = report(copy)
    assert result["label_source"] == "automatic, subdivided (loop x1)"
    assert result["converged"] and result["flipped_faces"] == 0, result
    assert len(key_names(copy)) == result["iterations"] + 1
    assert len(ico.data.vertices) == 42 and np.array_equal(vertices(ico), before)
    assert key_names(ico) == ["Basis", "Bulge"]


def test_running_again_replaces_the_copy_even_from_the_copy_itself():
    cube = _labelled_cube()
    deform(cube, iterations=50, subdivide=True, subdivide_levels=2)
    copy = bpy.data.objects["Cube polycube"]
    old_mesh = copy.data.name
    # The copy is now selected: deforming "it" with subdivide makes it again from the cube.
    assert deform(copy, iterations=50, subdivide=True, subdivide_levels=1) == {'FINISHED'}
    assert [obj.name for obj in bpy.data.objects] == ["Cube", "Cube polycube"]
    assert len(bpy.data.objects["Cube polycube"].data.polygons) == 6 * 4
    assert old_mesh not in bpy.data.meshes


def test_errors_leave_nothing_behind():
    cube = _labelled_cube()
    message = deform_error(cube, subdivide=True, subdivide_scheme='LOOP')
    assert "'Cube' was not deformed" in message and "triangle" in message, message
    assert [obj.name for obj in bpy.data.objects] == ["Cube"]
    stranger = bpy.data.objects.new("Cube polycube", bpy.data.meshes.new("Stranger"))
    bpy.context.scene.collection.objects.link(stranger)
    message = deform_error(cube, subdivide=True)
    assert "'Cube polycube' exists already" in message, message
    assert len(stranger.data.polygons) == 0 and report(stranger) is None


run_tests(globals())
