"""Animation: frame start + k shows iteration k, frames between blend linearly; the
sidebar's scrub slider."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    deform, enable_addon, evaluated_coordinates, key_coordinates, key_names, labelled_sphere,
    report, run_tests)

polycube = enable_addon()
START = 10


def _at(obj, frame, subframe=0.0):
    bpy.context.scene.frame_set(frame, subframe=subframe)
    return evaluated_coordinates(obj)


def _close(a, b):
    return np.abs(a - b).max() < 1e-5


def test_frame_start_plus_k_shows_iteration_k():
    sphere = labelled_sphere()
    deform(sphere, iterations=200, animate=True, start_frame=START, fit_frame_range=True)
    last = report(sphere)["iterations"]
    scene = bpy.context.scene
    assert (scene.frame_start, scene.frame_end) == (START, START + last)
    basis = key_coordinates(sphere, "Basis")
    assert _close(_at(sphere, START - 5), basis)
    assert _close(_at(sphere, START), basis)
    for k in range(1, last + 1):
        assert _close(_at(sphere, START + k), key_coordinates(sphere, f"Polycube {k:03d}")), k
    assert _close(_at(sphere, START + last + 20), key_coordinates(sphere, f"Polycube {last:03d}"))


def test_the_scene_frame_range_stays_unless_asked():
    sphere = labelled_sphere()
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 250
    deform(sphere, iterations=200, animate=True, start_frame=START)
    last = report(sphere)["iterations"]
    assert (scene.frame_start, scene.frame_end) == (1, 250)
    assert scene.frame_current == START + last  # the polycube shows


def test_frames_between_kept_iterations_blend_linearly():
    sphere = labelled_sphere()
    deform(sphere, iterations=12, tolerance=1e-4, variant='FIXED', keep='EVERY', keep_every=4,
           animate=True, start_frame=START)
    key = {k: key_coordinates(sphere, f"Polycube {k:03d}") for k in (4, 8, 12)}
    basis = key_coordinates(sphere, "Basis")
    assert _close(_at(sphere, START + 2), 0.5 * (basis + key[4]))
    assert _close(_at(sphere, START + 4), key[4])
    assert _close(_at(sphere, START + 5), 0.75 * key[4] + 0.25 * key[8])
    assert _close(_at(sphere, START + 6, 0.5), 0.375 * key[4] + 0.625 * key[8])
    assert _close(_at(sphere, START + 12), key[12])
    fcurves = sphere.data.shape_keys.animation_data.action.fcurves
    assert all(point.interpolation == 'LINEAR' for fcurve in fcurves for point in fcurve.keyframe_points)


def test_running_again_without_animation_drops_the_keyframes():
    sphere = labelled_sphere()
    deform(sphere, iterations=200, animate=True)
    deform(sphere, iterations=8, tolerance=1e-4, variant='FIXED')
    action = sphere.data.shape_keys.animation_data.action
    assert len(action.fcurves) == 0, [fcurve.data_path for fcurve in action.fcurves]
    assert "animation_frames" not in report(sphere)
    assert _close(_at(sphere, 3), key_coordinates(sphere, "Polycube 008"))


def test_scrub_slider_blends_kept_iterations():
    sphere = labelled_sphere()
    deform(sphere, iterations=10, tolerance=1e-4, variant='FIXED', keep='EVERY', keep_every=5)
    assert sphere.polycube_scrub == 1.0  # the run ends showing the polycube
    five, ten = key_coordinates(sphere, "Polycube 005"), key_coordinates(sphere, "Polycube 010")
    sphere.polycube_scrub = 0.7  # iteration 7: between the keys of 5 and 10
    assert abs(sphere.polycube_scrub - 0.7) < 1e-6
    assert _close(evaluated_coordinates(sphere), 0.6 * five + 0.4 * ten)
    sphere.polycube_scrub = 0.0
    assert _close(evaluated_coordinates(sphere), key_coordinates(sphere, "Basis"))
    assert polycube.scrub.shown_iteration(sphere) == 0.0


def test_scrub_slider_moves_the_frame_when_animated():
    sphere = labelled_sphere()
    deform(sphere, iterations=20, tolerance=1e-4, variant='FIXED', animate=True, start_frame=START)
    sphere.polycube_scrub = 0.25
    assert bpy.context.scene.frame_current == START + 5
    assert _close(evaluated_coordinates(sphere), key_coordinates(sphere, "Polycube 005"))
    assert abs(sphere.polycube_scrub - 0.25) < 1e-6
    assert len(key_names(sphere)) == 21


run_tests(globals())
