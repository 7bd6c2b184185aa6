# SPDX-License-Identifier: GPL-3.0-or-later
"""The sidebar slider that scrubs from the input through the kept iterations.

`Object.polycube_scrub` stores nothing: it reads and writes the shape-key values
(or, when they are animated, the scene frame), so it always shows what the
viewport shows. 0 is the input, 1 the last kept iteration.
"""

import bisect

import bpy
from bpy.props import FloatProperty

from .animation import is_animated
from .report import load_report
from .shape_keys import polycube_keys


def shown_iteration(obj):
    """The iteration the object shows now (fractional between two kept ones), or None."""
    keys = polycube_keys(obj)
    if not keys:
        return None
    start = _animation_start(obj)
    if start is not None:
        scene = bpy.context.scene
        frame = scene.frame_current + scene.frame_subframe
        return min(max(frame - start, 0.0), float(keys[-1][0]))
    # Scrubbing sets at most two neighbouring keys whose values add up to one, so
    # the value-weighted iteration is where the slider stands.
    return sum(iteration * block.value for iteration, block in keys)


def show_iteration(obj, position):
    keys = polycube_keys(obj)
    if not keys:
        return
    start = _animation_start(obj)
    if start is not None:
        frame = start + position
        bpy.context.scene.frame_set(int(frame), subframe=frame - int(frame))
        return
    iterations = [0] + [iteration for iteration, _ in keys]
    upper = min(max(bisect.bisect_left(iterations, position), 1), len(iterations) - 1)
    low, high = iterations[upper - 1], iterations[upper]
    weight = (position - low) / (high - low)
    for j, (_, block) in enumerate(keys, start=1):
        block.value = weight if j == upper else (1.0 - weight if j == upper - 1 else 0.0)


def _animation_start(obj):
    report = load_report(obj)
    if report is None or "animation_frames" not in report or not is_animated(obj):
        return None
    return report["animation_frames"][0]


def _get(obj):
    keys = polycube_keys(obj)
    if not keys:
        return 0.0
    return min(max(shown_iteration(obj) / keys[-1][0], 0.0), 1.0)


def _set(obj, value):
    keys = polycube_keys(obj)
    if keys:
        show_iteration(obj, value * keys[-1][0])


def register():
    bpy.types.Object.polycube_scrub = FloatProperty(
        name="Scrub",
        description="Show the mesh from its input (0) through the kept iterations to the polycube (1)",
        subtype='FACTOR', min=0.0, max=1.0, get=_get, set=_set)


def unregister():
    del bpy.types.Object.polycube_scrub
