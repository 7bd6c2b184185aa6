# SPDX-License-Identifier: GPL-3.0-or-later
"""Keyframes on the Polycube shape keys: frame start + k shows iteration k exactly.

Each key rises linearly from 0 at the previous kept iteration's frame to 1 at its
own and falls back to 0 at the next one, so any frame between two kept iterations
is their linear blend and every other key stays at 0.
"""

from .shape_keys import key_iteration, polycube_keys


def animate(obj, start_frame):
    """Keyframe the object's Polycube keys; returns the frame of the last one."""
    keys = polycube_keys(obj)
    frames = [start_frame] + [start_frame + iteration for iteration, _ in keys]
    for j, (_, block) in enumerate(keys, start=1):
        points = [(frames[j - 1], 0.0), (frames[j], 1.0)]
        if j + 1 < len(frames):
            points.append((frames[j + 1], 0.0))
        for frame, value in points:
            block.value = value
            block.keyframe_insert("value", frame=frame)
    for fcurve in _polycube_fcurves(obj):
        for point in fcurve.keyframe_points:
            point.interpolation = 'LINEAR'
    return frames[-1]


def is_animated(obj):
    return any(True for _ in _polycube_fcurves(obj))


def clear_animation(obj):
    """Drop the keyframes of the Polycube keys; Blender keeps them when a key goes."""
    fcurves = _fcurves(obj)
    if fcurves is not None:
        for fcurve in list(_polycube_fcurves(obj)):
            fcurves.remove(fcurve)


def _fcurves(obj):
    key = obj.data.shape_keys
    anim = key.animation_data if key is not None else None
    action = anim.action if anim is not None else None
    if action is None:
        return None
    if hasattr(action, "fcurves"):
        return action.fcurves
    # Blender 5.0 keeps F-curves per action slot only.
    from bpy_extras import anim_utils
    channelbag = anim_utils.action_get_channelbag_for_slot(action, anim.action_slot)
    return channelbag.fcurves if channelbag is not None else None


def _polycube_fcurves(obj):
    fcurves = _fcurves(obj)
    for fcurve in fcurves or ():
        path = fcurve.data_path
        if path.startswith('key_blocks["') and path.endswith('"].value'):
            if key_iteration(path[len('key_blocks["'):-len('"].value')]) is not None:
                yield fcurve
