"""Runs that stop moving are stopped (no identical shape keys), and the advice
says what happened: folds or collapse, and where the labels came from."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    add_attribute, deform, enable_addon, key_coordinates, key_names, report, run_tests, select_only, vertices)

polycube = enable_addon()


def _suzanne_subdivided_twice():
    bpy.ops.mesh.primitive_monkey_add()
    monkey = bpy.context.active_object
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    for _ in range(2):
        bpy.ops.mesh.subdivide(number_cuts=1)
    bpy.ops.object.mode_set(mode='OBJECT')
    assert len(monkey.data.polygons) == 8000
    return monkey


def _sphere_labelled_plus_z():
    """Every face asked to face +Z: folds no iteration can undo, so the run stops moving."""
    bpy.ops.mesh.primitive_uv_sphere_add()
    sphere = bpy.context.active_object
    add_attribute(sphere.data, "polycube_label", 'INT', np.full(len(sphere.data.polygons), 4, np.int32))
    return sphere


def test_a_run_that_stops_moving_stops_without_identical_keys():
    sphere = _sphere_labelled_plus_z()
    deform(sphere, iterations=60)
    result = report(sphere)
    assert result["stalled_at"] < 60 and result["iterations"] == result["stalled_at"], result
    assert result["moved_until"] == result["kept_iterations"][-1] < result["stalled_at"]
    assert result["stalled_at"] - result["moved_until"] == polycube.progress_watch.STILL_ITERATIONS
    # Every key shows a different shape.
    diagonal = np.linalg.norm(np.ptp(vertices(sphere), axis=0))
    shapes = [vertices(sphere)] + [key_coordinates(sphere, name) for name in key_names(sphere)[1:]]
    steps = [np.abs(b - a).max() for a, b in zip(shapes, shapes[1:])]
    assert min(steps) > polycube.progress_watch.STILL_FRACTION * diagonal, steps
    assert polycube.report.outcome(result) == "no progress"
    hint = polycube.report.advice(result)
    refused = [attempt for attempt in result["flatten_attempts"] if not attempt["kept"]]
    assert refused and refused[-1]["folds_left"] > 0, result["flatten_attempts"]
    assert any(f"would leave {refused[-1]['folds_left']} folded faces" in line for line in hint), hint
    assert hint[-1] == "Try Auto Label, or relabel the unconverged faces", hint


def test_advice_for_nearest_axis_labels_suggests_auto_label():
    # A run that stalled on nearest-axis labels (Suzanne subdivided twice did, before the
    # solver untangled flat charts): the report as the operator stores it.
    stalled = {"converged": False, "stopped": True, "stalled_at": 17, "moved_until": 9, "labelled_faces": 0,
               "flatten_attempts": [{"kept": 0, "folds_left": 410, "collapsed_area": 0.2}]}
    assert polycube.report.advice(stalled) == [
        "The mesh stopped moving after iteration 9; stopped at iteration 17",
        "Flat charts would leave 410 folded faces (and collapse 20% of the surface)",
        "Every face took its nearest axis: try Auto Label"]


def test_advice_after_auto_label_does_not_suggest_auto_label():
    monkey = _suzanne_subdivided_twice()
    select_only(monkey)
    assert bpy.ops.object.polycube_auto_label() == {'FINISHED'}
    deform(monkey, iterations=60)
    result = report(monkey)
    assert result["labels_automatic"], result
    hint = polycube.report.advice(result)
    if not result["converged"]:
        assert hint and not any("try Auto Label" in line for line in hint), hint
        assert "automatic labels" in hint[-1], hint


def test_a_polycube_run_to_the_end_with_tolerance_zero_writes_no_still_keys():
    bpy.ops.mesh.primitive_uv_sphere_add()
    sphere = bpy.context.active_object
    deform(sphere, iterations=40, tolerance=0.0)
    result = report(sphere)
    # Tolerance 0 asks for every iteration: the run is not cut short, but the
    # iterations after the polycube stood still get no shape key.
    assert result["iterations"] == 40 and "stalled_at" not in result, result
    assert result["kept_iterations"][-1] < 40 and result["normal_deviation_max_deg"] < 1e-6, result


run_tests(globals())
