"""Bad input: one clear sentence through the operator's report, nothing changed."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    add_attribute, assert_untouched, deform, deform_error, enable_addon, key_names,
    labelled_sphere, report, run_tests, select_only, vertices)

polycube = enable_addon()


def _one_sentence(message, *fragments):
    assert message.startswith("Error: "), message
    text = message[len("Error: "):].strip()
    assert text.count(". ") == 0 and text.endswith("."), text
    for fragment in fragments:
        assert fragment in text, (fragment, text)


def _object(name, vertices=(), edges=(), faces=()):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(list(vertices), list(edges), list(faces))
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def test_empty_mesh():
    empty = _object("Empty mesh")
    _one_sentence(deform_error(empty), "'Empty mesh'", "empty")
    assert_untouched(empty, vertices(empty))


def test_mesh_without_faces():
    wire = _object("Wire", [(0, 0, 0), (1, 0, 0), (1, 1, 0)], [(0, 1), (1, 2)])
    _one_sentence(deform_error(wire), "'Wire'", "no faces")
    assert_untouched(wire, vertices(wire))


def test_faces_without_area():
    flat = _object("Point", [(0, 0, 0)] * 4, faces=[(0, 1, 2), (0, 2, 3)])
    _one_sentence(deform_error(flat), "'Point'", "zero area")
    assert_untouched(flat, vertices(flat))


def test_nan_coordinates():
    sphere = labelled_sphere()
    before = vertices(sphere)
    before[5, 0], before[9, 2] = float("nan"), float("inf")
    sphere.data.vertices.foreach_set("co", before.astype(np.float32).ravel())
    _one_sentence(deform_error(sphere), "'Sphere'", "2 vertices have NaN")
    assert_untouched(sphere, before)


def test_non_mesh_object_alone():
    bpy.ops.object.camera_add()
    camera = bpy.context.active_object
    _one_sentence(deform_error(camera), f"'{camera.name}'", "camera, not a mesh")
    assert "polycube_report" not in camera.keys()


def test_an_empty_object_is_named_with_its_article():
    bpy.ops.object.empty_add()
    empty = bpy.context.active_object
    _one_sentence(deform_error(empty), f"'{empty.name}': it is an empty, not a mesh")


def test_auto_label_failure_is_an_error_scripts_see():
    # A warning with CANCELLED would pass silently in a script; an error raises.
    empty = _object("Empty mesh")
    select_only(empty)
    try:
        bpy.ops.object.polycube_auto_label()
    except RuntimeError as error:
        _one_sentence(str(error), "'Empty mesh'", "empty")
    else:
        raise AssertionError("Auto Label on an empty mesh reported no error")
    assert "polycube_label" not in empty.data.attributes


def test_subdivision_levels_go_as_far_as_the_native_refine():
    levels = bpy.ops.object.polycube_deform.get_rna_type().properties["subdivide_levels"]
    assert levels.hard_max == polycube.polycube_native.MAX_REFINE_LEVELS == 8


def test_non_mesh_beside_a_mesh_is_skipped_and_the_mesh_deformed():
    sphere = labelled_sphere()
    bpy.ops.object.light_add(type='POINT')
    light = bpy.context.active_object
    select_only(light, sphere)
    assert bpy.ops.object.polycube_deform(iterations=200) == {'FINISHED'}
    assert report(sphere)["converged"]
    assert "polycube_report" not in light.keys()


def test_junk_labels_leave_earlier_results_alone():
    sphere = labelled_sphere()
    deform(sphere, iterations=200)
    names, first_report = key_names(sphere), report(sphere)
    add_attribute(sphere.data, "polycube_label", 'INT', np.full(len(sphere.data.polygons), 6, np.int32))
    _one_sentence(deform_error(sphere), "polycube_label", "6")
    assert key_names(sphere) == names and report(sphere) == first_report


def test_bad_object_beside_a_good_one():
    sphere = labelled_sphere()
    empty = _object("Empty mesh")
    select_only(empty, sphere)
    assert bpy.ops.object.polycube_deform(iterations=200) == {'FINISHED'}
    assert report(sphere)["converged"]
    assert_untouched(empty, vertices(empty))


def test_edit_mode_is_refused_by_poll():
    sphere = labelled_sphere()
    select_only(sphere)
    bpy.ops.object.mode_set(mode='EDIT')
    try:
        bpy.ops.object.polycube_deform()
    except RuntimeError as error:
        assert "Object Mode" in str(error), error
    else:
        raise AssertionError("ran in edit mode")
    finally:
        bpy.ops.object.mode_set(mode='OBJECT')
    assert sphere.data.shape_keys is None


def test_nothing_selected_is_refused_by_poll():
    labelled_sphere()
    bpy.ops.object.select_all(action='DESELECT')
    assert not bpy.ops.object.polycube_deform.poll()


def test_settings_out_of_range_are_clamped_not_crashing():
    sphere = labelled_sphere()
    deform(sphere, iterations=0, tolerance=-1.0, keep_every=0)
    result = report(sphere)
    assert result["iterations"] == 1 and result["tolerance_deg"] == 0  # clamped to 0: every iteration


run_tests(globals())
