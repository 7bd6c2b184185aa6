# SPDX-License-Identifier: GPL-3.0-or-later
"""The finished polycube of an object, for its uses (UV map, quad remesh): the last
run's final shape key and the labels the solver ended with."""

from .mesh_arrays import read_mesh_arrays
from .report import load_labels_used
from .shape_keys import polycube_keys, read_key


def has_polycube(obj):
    return obj is not None and obj.type == 'MESH' and bool(polycube_keys(obj))


def polycube_of(obj):
    """(MeshArrays of the base mesh, polycube positions (n, 3), labels or None);
    ValueError with one sentence when the object has no usable polycube."""
    if obj is None or obj.type != 'MESH':
        raise ValueError("it is not a mesh")
    keys = polycube_keys(obj)
    if not keys:
        raise ValueError("it has no polycube yet: run Deform to Polycube first")
    mesh = read_mesh_arrays(obj.data)
    positions = read_key(keys[-1][1])
    if len(positions) != len(mesh.vertices):
        raise ValueError("its mesh changed since it was deformed: deform it again")
    labels = load_labels_used(obj)
    if labels is not None and len(labels) != len(mesh.face_sizes):
        labels = None  # faces changed since: read the labels from the polycube instead
    return mesh, positions, labels


def poll_polycube(cls, context):
    """Shared poll of the operators that use an object's polycube."""
    if context.mode != 'OBJECT':
        cls.poll_message_set("Switch to Object Mode first")
        return False
    if not has_polycube(context.active_object):
        cls.poll_message_set("Deform the active mesh to its polycube first")
        return False
    return True
