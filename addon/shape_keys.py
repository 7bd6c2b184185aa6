# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's shape keys: a Basis plus one relative key per kept iteration.

Keys are named `Polycube 001`, `Polycube 002`, ... after the iteration they hold, so
they sort and the user's own keys (any other name) are never touched.
"""

import re

from .mesh_arrays import read_coordinates, write_coordinates

KEY_PREFIX = "Polycube "
_KEY_NAME = re.compile(re.escape(KEY_PREFIX) + r"(\d+)")


def key_name(iteration, max_iterations):
    # Zero-padded to the widest number the run can reach so names sort numerically.
    width = max(3, len(str(max_iterations)))
    return f"{KEY_PREFIX}{iteration:0{width}d}"


def key_iteration(name):
    """The iteration a key holds, or None when it is not one of ours."""
    match = _KEY_NAME.fullmatch(name)
    return int(match.group(1)) if match else None


def polycube_keys(obj):
    """[(iteration, key block)] of the object's Polycube keys, by iteration."""
    key = obj.data.shape_keys
    if key is None:
        return []
    found = [(key_iteration(block.name), block) for block in key.key_blocks]
    return sorted(((i, block) for i, block in found if i is not None), key=lambda pair: pair[0])


def remove_polycube_keys(obj):
    for _, block in polycube_keys(obj):
        obj.shape_key_remove(block)


def ensure_basis(obj):
    """The reference key every Polycube key is relative to, added when missing."""
    key = obj.data.shape_keys
    if key is None:
        return obj.shape_key_add(name="Basis", from_mix=False)
    key.use_relative = True
    return key.reference_key


def _points(block):
    # ShapeKey.points (Blender 4.1+) is the typed, faster path; `data` everywhere else.
    return getattr(block, "points", block.data)


def add_key(obj, name, positions):
    basis = ensure_basis(obj)
    block = obj.shape_key_add(name=name, from_mix=False)
    block.relative_key = basis
    write_coordinates(_points(block), positions)
    block.value = 0.0
    return block


def read_key(block):
    return read_coordinates(_points(block), len(block.data))


def show_only(obj, shown_block):
    """Value 1 on one Polycube key and 0 on the others (the user's keys keep theirs)."""
    for _, block in polycube_keys(obj):
        block.value = 1.0 if block == shown_block else 0.0
