"""The operator on a labelled UV sphere: shape keys, figures, re-runs, user keys, undo."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    arrays, deform, enable_addon, key_coordinates, key_figures, key_names, labelled_sphere,
    nearest_axis_labels, report, run_tests, select_only, vertices)

polycube = enable_addon()
TOLERANCE = 0.5


def test_sphere_becomes_a_polycube_with_a_key_per_iteration():
    sphere = labelled_sphere()
    labels = nearest_axis_labels(sphere)
    assert deform(sphere, iterations=200, tolerance=TOLERANCE) == {'FINISHED'}
    result = report(sphere)
    n = result["iterations"]
    assert result["converged"] and not result["stopped"] and 1 < n < 200, result
    assert key_names(sphere) == ["Basis"] + [f"Polycube {k:03d}" for k in range(1, n + 1)]
    assert result["kept_iterations"] == list(range(1, n + 1))

    final = key_figures(sphere, f"Polycube {n:03d}", labels)
    assert final["normal_deviation_max_deg"] < TOLERANCE, final
    assert final["flipped_faces"] == 0, final
    # The stored report describes the key that was written (float32 in Blender).
    assert abs(final["normal_deviation_max_deg"] - result["normal_deviation_max_deg"]) < 0.05
    assert final["collapsed_faces"] == result["collapsed_faces"]
    assert abs(final["edge_error"] - result["edge_error"]) < 1e-4
    first = key_figures(sphere, "Polycube 001", labels)
    assert first["normal_deviation_mean_deg"] > 10 * final["normal_deviation_mean_deg"]

    blocks = sphere.data.shape_keys.key_blocks
    assert all(block.relative_key == blocks["Basis"] for block in blocks)
    assert [block.value for block in blocks][1:] == [0.0] * (n - 1) + [1.0]
    assert sphere.active_shape_key_index == n


def test_basis_is_the_input_and_the_mesh_is_not_changed():
    sphere = labelled_sphere()
    before = arrays(sphere)
    raw = vertices(sphere)
    deform(sphere, iterations=200)
    assert np.array_equal(key_coordinates(sphere, "Basis"), raw)
    assert np.array_equal(vertices(sphere), raw)
    after = arrays(sphere)
    assert np.array_equal(after.face_indices, before.face_indices)
    assert np.array_equal(after.face_sizes, before.face_sizes)
    # Every key moves the vertices; none is a copy of the input.
    for name in key_names(sphere)[1:]:
        assert np.abs(key_coordinates(sphere, name) - raw).max() > 1e-3, name


def test_a_second_run_replaces_the_polycube_keys():
    sphere = labelled_sphere()
    deform(sphere, iterations=200, variant='FIXED')
    assert len(key_names(sphere)) > 11
    # A tolerance the plain variant does not reach in 10 iterations: exactly
    # the 10 asked for (the default reaches exact polycubes, 0 degrees).
    deform(sphere, iterations=10, tolerance=1e-4, variant='FIXED')
    assert key_names(sphere) == ["Basis"] + [f"Polycube {k:03d}" for k in range(1, 11)]
    assert report(sphere)["iterations"] == 10 and not report(sphere)["converged"]


def test_users_own_shape_keys_are_left_alone():
    sphere = labelled_sphere()
    sphere.shape_key_add(name="Rest", from_mix=False)
    smile = sphere.shape_key_add(name="Smile", from_mix=False)
    moved = vertices(sphere) * 1.25
    smile.data.foreach_set("co", moved.astype(np.float32).ravel())
    smile.value = 0.3
    smile.slider_max = 2.0
    deform(sphere, iterations=20, tolerance=1e-4, variant='FIXED')
    later = sphere.shape_key_add(name="Polycube notes", from_mix=False)  # not one of ours
    deform(sphere, iterations=5, tolerance=1e-4, variant='FIXED')

    names = key_names(sphere)
    assert names[:2] == ["Rest", "Smile"] and "Polycube notes" in names, names
    assert [name for name in names if name.startswith("Polycube 0")] == \
        [f"Polycube {k:03d}" for k in range(1, 6)]
    blocks = sphere.data.shape_keys.key_blocks
    assert np.array_equal(key_coordinates(sphere, "Smile"), moved.astype(np.float32))
    assert abs(blocks["Smile"].value - 0.3) < 1e-6 and blocks["Smile"].slider_max == 2.0
    assert later.name == "Polycube notes"
    # Ours are relative to the user's reference key; no second Basis appears.
    assert "Basis" not in names
    assert blocks["Polycube 005"].relative_key == blocks["Rest"]


def test_keep_every_kth_and_final_only():
    sphere = labelled_sphere()
    deform(sphere, iterations=10, tolerance=1e-4, variant='FIXED', keep='ALL')
    tenth = key_coordinates(sphere, "Polycube 010")
    fourth = key_coordinates(sphere, "Polycube 004")

    deform(sphere, iterations=10, tolerance=1e-4, variant='FIXED', keep='EVERY', keep_every=4)
    assert key_names(sphere) == ["Basis", "Polycube 004", "Polycube 008", "Polycube 010"]
    assert report(sphere)["kept_iterations"] == [4, 8, 10]
    assert np.array_equal(key_coordinates(sphere, "Polycube 004"), fourth)
    assert np.array_equal(key_coordinates(sphere, "Polycube 010"), tenth)

    deform(sphere, iterations=10, tolerance=1e-4, variant='FIXED', keep='FINAL')
    assert key_names(sphere) == ["Basis", "Polycube 010"]
    assert np.array_equal(key_coordinates(sphere, "Polycube 010"), tenth)


def test_key_names_widen_for_a_thousand_iterations_or_more():
    sphere = labelled_sphere()
    deform(sphere, iterations=1000, tolerance=TOLERANCE, keep='FINAL')
    (name,) = key_names(sphere)[1:]
    assert name == f"Polycube {report(sphere)['iterations']:04d}", name


def test_current_variant():
    sphere = labelled_sphere()
    labels = nearest_axis_labels(sphere)
    deform(sphere, iterations=30, variant='CURRENT', tolerance=1e-4)
    result = report(sphere)
    assert result["variant"] == "current" and result["iterations"] == 30
    start = polycube.polycube_native.figures(arrays(sphere).vertices, vertices(sphere),
                                             arrays(sphere).face_indices, arrays(sphere).face_sizes, labels)
    final = key_figures(sphere, "Polycube 030", labels)
    assert final["normal_deviation_mean_deg"] < 0.2 * start["normal_deviation_mean_deg"], (start, final)


def test_quick_further_runs_reach_the_solver():
    # Off by default; the operator's settings are the module's rerun_from_result
    # and coarse_triangles (the coarse route, docs/design.md section 2.8).
    sphere = labelled_sphere()
    native = polycube.polycube_native
    original, seen = native.deform, []

    def spy(*args, **kwargs):
        seen.append((kwargs.get("rerun_from_result"), kwargs.get("coarse_triangles")))
        return original(*args, **kwargs)

    native.deform = spy
    try:
        assert deform(sphere, iterations=5) == {'FINISHED'}
        assert deform(sphere, iterations=5, rerun_from_result=True) == {'FINISHED'}
        assert deform(sphere, iterations=5, coarse_triangles=0) == {'FINISHED'}
    finally:
        native.deform = original
    default = native.DEFAULT_COARSE_TRIANGLES
    assert default > 0
    assert seen == [(False, default), (True, default), (False, 0)]


def test_same_settings_same_keys():
    sphere = labelled_sphere()
    deform(sphere, iterations=15, tolerance=1e-4, variant='FIXED')
    first = key_coordinates(sphere, "Polycube 015")
    deform(sphere, iterations=15, tolerance=1e-4, variant='FIXED')
    assert np.array_equal(key_coordinates(sphere, "Polycube 015"), first)


def test_several_objects_at_once_and_a_shared_mesh_only_once():
    one = labelled_sphere("One")
    two = labelled_sphere("Two", location=(3, 0, 0))
    twin = one.copy()  # a linked duplicate: same mesh, same shape keys
    bpy.context.scene.collection.objects.link(twin)
    twin.name = "Twin"
    select_only(one, two, twin)
    assert bpy.ops.object.polycube_deform(iterations=200) == {'FINISHED'}
    for obj in (one, two):
        assert report(obj)["converged"], obj.name
        assert len(key_names(obj)) == report(obj)["iterations"] + 1
    assert "polycube_report" not in twin.keys()


def test_an_object_that_is_already_a_polycube():
    bpy.ops.mesh.primitive_cube_add()
    cube = bpy.context.active_object
    assert deform(cube) == {'FINISHED'}
    result = report(cube)
    assert result["iterations"] == 0 and result["converged"] and result["normal_deviation_max_deg"] < 1e-6
    assert cube.data.shape_keys is None


def test_undo_restores_the_object():
    sphere = labelled_sphere()
    raw = vertices(sphere)
    # Background Blender pushes no undo step after an operator called from Python
    # (the UI test checks the operator's own step); push them as the UI would.
    bpy.ops.ed.undo_push(message="before deform")
    deform(sphere, iterations=200)
    bpy.ops.ed.undo_push(message="Deform to Polycube")
    assert len(key_names(bpy.data.objects["Sphere"])) > 1
    bpy.ops.ed.undo()
    sphere = bpy.data.objects["Sphere"]  # undo reloads the data: look it up again
    assert sphere.data.shape_keys is None
    assert "polycube_report" not in sphere.keys()
    assert np.array_equal(vertices(sphere), raw)
    bpy.ops.ed.redo()
    assert report(bpy.data.objects["Sphere"])["converged"]


def test_scene_settings_match_the_operator_defaults():
    # The sidebar's copy of the settings starts where the operator does.
    operator = bpy.ops.object.polycube_deform.get_rna_type().properties
    settings = bpy.context.scene.polycube
    for name in ("iterations", "tolerance", "variant", "rerun_from_result", "coarse_triangles", "keep", "keep_every", "animate",
                 "start_frame",
                 "label_source", "detail", "subdivide", "subdivide_levels", "subdivide_scheme"):
        assert getattr(settings, name) == operator[name].default, name


run_tests(globals())
