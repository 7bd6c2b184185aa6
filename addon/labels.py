# SPDX-License-Identifier: GPL-3.0-or-later
"""Per-face polycube labels as a Blender mesh stores them (docs/design.md section 3).

Three stores, strongest first:
- our own INT face attribute `polycube_label` (values -1..5);
- face maps (Blender 3.x), by name;
- what Blender 4.0+ made of face maps: an INT face attribute `face_maps` holding
  each face's old map index, plus one BOOLEAN face attribute per old map, named
  after it.
Faces left at -1 are unlabelled; the solver gives them their nearest axis.

In Edit Mode the mesh's attribute data is empty until Edit Mode is left: every
store is then read through `bmesh`, which holds the faces being edited.
"""

from typing import NamedTuple

import bmesh
import numpy as np

from .label_names import ACCEPTED_SPELLINGS, label_from_name
from .polycube_native import LABEL_NAMES

LABEL_ATTRIBUTE = "polycube_label"
FACE_MAPS_ATTRIBUTE = "face_maps"


class Labels(NamedTuple):
    values: np.ndarray  # int32 per face, -1 = unlabelled
    source: str         # where they came from, for the panel and the report


NO_LABELS = "none (nearest axis)"


def read_labels(obj):
    """The labels of a mesh object (Object or Edit Mode); ValueError with one sentence
    when they are junk."""
    mesh = obj.data
    faces = _FaceData(mesh)
    attribute = mesh.attributes.get(LABEL_ATTRIBUTE)
    if attribute is not None:
        return Labels(_read_label_attribute(faces, attribute), f"attribute {LABEL_ATTRIBUTE}")
    if len(getattr(obj, "face_maps", ())):
        return Labels(_read_face_maps(obj, faces), "face maps")
    attribute = mesh.attributes.get(FACE_MAPS_ATTRIBUTE)
    if attribute is not None:
        return Labels(_read_face_maps_attribute(faces, attribute), f"attribute {FACE_MAPS_ATTRIBUTE}")
    return Labels(np.full(faces.count, -1, dtype=np.int32), NO_LABELS)


class _FaceData:
    """Per-face values of a mesh: from its attributes in Object Mode, from its
    bmesh in Edit Mode."""

    def __init__(self, mesh):
        self.mesh = mesh
        self.bmesh = bmesh.from_edit_mesh(mesh) if mesh.is_editmode else None
        self.count = len(self.bmesh.faces) if self.bmesh is not None else len(mesh.polygons)

    def values(self, name, kind):
        """The values of the face attribute `name`, kind 'int' or 'bool'."""
        dtype = np.int32 if kind == 'int' else bool
        if self.bmesh is None:
            values = np.empty(self.count, dtype=dtype)
            self.mesh.attributes[name].data.foreach_get("value", values)
            return values
        layers = getattr(self.bmesh.faces.layers, kind, None)
        layer = layers.get(name) if layers is not None else None
        if layer is None:
            raise ValueError(f"attribute {name} cannot be read in Edit Mode; switch to Object Mode")
        return np.fromiter((face[layer] for face in self.bmesh.faces), dtype=dtype, count=self.count)

    def face_map_indices(self):
        """Each face's face map index (Blender 3.x), -1 = none."""
        if self.bmesh is None:
            if not len(self.mesh.face_maps):
                # Face maps exist on the object but no face was ever assigned to one.
                return np.full(self.count, -1, dtype=np.int32)
            values = np.empty(self.count, dtype=np.int32)
            self.mesh.face_maps[0].data.foreach_get("value", values)
            return values
        layer = self.bmesh.faces.layers.face_map.active
        if layer is None:
            return np.full(self.count, -1, dtype=np.int32)
        return np.fromiter((face[layer] for face in self.bmesh.faces), dtype=np.int32, count=self.count)

    def set_face_map_indices(self, values):
        if self.bmesh is None:
            if not len(self.mesh.face_maps):
                self.mesh.face_maps.new()
            self.mesh.face_maps[0].data.foreach_set("value", values)
            return
        layer = self.bmesh.faces.layers.face_map.verify()
        for face, value in zip(self.bmesh.faces, values.tolist()):
            face[layer] = value


def label_counts(values):
    """Faces per label in LABEL_NAMES order, then the unlabelled ones."""
    counts = np.bincount(values + 1, minlength=len(LABEL_NAMES) + 1)
    return [int(c) for c in counts[1:]], int(counts[0])


def write_label_attribute(mesh, values):
    attribute = mesh.attributes.get(LABEL_ATTRIBUTE)
    if attribute is None:
        attribute = mesh.attributes.new(LABEL_ATTRIBUTE, 'INT', 'FACE')
    attribute.data.foreach_set("value", np.asarray(values, dtype=np.int32))


def write_face_maps(obj, values):
    """Blender 3.x only: put the faces into face maps named as in LABEL_NAMES, in Object
    or Edit Mode (then through bmesh: the caller updates the edit mesh).

    Maps of those names are ours: refilled, and removed when left empty. A face
    belongs to one face map at most, so faces in a user's other map (a name that
    is no label, such as 'Notes') stay there and keep their label in the
    attribute only; faces in a label map of another spelling ('PX') move to ours.
    Returns how many faces stayed in the user's maps.
    """
    values = np.asarray(values, dtype=np.int32)
    faces = _FaceData(obj.data)
    current = faces.face_map_indices()
    # One slot past the maps stands for "in no map".
    users = np.array([label_from_name(face_map.name) is None for face_map in obj.face_maps] + [False])
    stays = users[np.where(current >= 0, current, len(users) - 1)]
    map_of_label = np.full(len(LABEL_NAMES) + 1, -1, dtype=np.int32)  # last slot: unlabelled
    for label in np.unique(values[~stays & (values >= 0)]):
        name = LABEL_NAMES[label]
        map_of_label[label] = (obj.face_maps.get(name) or obj.face_maps.new(name=name)).index
    faces.set_face_map_indices(np.where(stays, current, map_of_label[values]))
    empty = [name for label, name in enumerate(LABEL_NAMES)
             if map_of_label[label] < 0 and name in obj.face_maps]
    for name in empty:
        obj.face_maps.remove(obj.face_maps[name])  # Blender renumbers the later maps' faces
    return int(stays.sum())


def _read_int_face_attribute(faces, attribute):
    if attribute.domain != 'FACE' or attribute.data_type != 'INT':
        raise ValueError(
            f"attribute {attribute.name} must be an integer face attribute, "
            f"not {attribute.data_type} on {attribute.domain}")
    return faces.values(attribute.name, 'int')


def _read_label_attribute(faces, attribute):
    values = _read_int_face_attribute(faces, attribute)
    junk = (values < -1) | (values >= len(LABEL_NAMES))
    if junk.any():
        shown = ", ".join(str(v) for v in np.unique(values[junk])[:5])
        raise ValueError(
            f"attribute {LABEL_ATTRIBUTE} holds {shown} on {int(junk.sum())} faces, but labels are "
            f"-1 (none) or 0..5 for {', '.join(LABEL_NAMES)}")
    return values


def _labels_from_map_indices(map_indices, map_names):
    """Labels from face-map indices and the maps' names; junk names are an error."""
    in_map = (map_indices >= 0) & (map_indices < len(map_names))
    used = [int(i) for i in np.unique(map_indices[in_map])]
    unnamed = [i for i in used if map_names[i] is None]
    if unnamed:
        raise ValueError(
            f"face map {unnamed[0]} in attribute {FACE_MAPS_ATTRIBUTE} has no boolean face "
            f"attribute giving its name")
    unknown = [map_names[i] for i in used if label_from_name(map_names[i]) is None]
    if unknown:
        names = ", ".join(f"'{name}'" for name in unknown)
        plural = len(unknown) > 1
        raise ValueError(
            f"face map{'s' if plural else ''} {names} {'are' if plural else 'is'} not "
            f"an axis; name face maps {ACCEPTED_SPELLINGS}")
    # One slot past the maps stands for "in no map".
    table = np.full(len(map_names) + 1, -1, dtype=np.int32)
    for i in used:
        table[i] = label_from_name(map_names[i])
    return table[np.where(in_map, map_indices, len(map_names))]


def _read_face_maps(obj, faces):
    return _labels_from_map_indices(faces.face_map_indices(), [face_map.name for face_map in obj.face_maps])


def _read_face_maps_attribute(faces, attribute):
    map_indices = _read_int_face_attribute(faces, attribute)
    map_count = int(map_indices.max()) + 1 if faces.count else 0
    return _labels_from_map_indices(map_indices, _face_map_names(faces, map_indices, map_count))


def _face_map_names(faces, map_indices, map_count):
    """Name each old face map after the boolean face attribute that matches its faces.

    Blender 4.0 keeps no index-to-name table, so match by content: map i is named
    after the BOOLEAN face attribute whose faces overlap {face_maps == i} best
    (intersection over union above one half; among equals an axis name wins, since
    Blender's own booleans such as sharp_face may coincide with a map).
    """
    candidates = []
    for attribute in faces.mesh.attributes:
        if (attribute.domain == 'FACE' and attribute.data_type == 'BOOLEAN'
                and not attribute.name.startswith(".")):
            candidates.append((attribute.name, faces.values(attribute.name, 'bool')))
    names = []
    for index in range(map_count):
        members = map_indices == index
        best, best_score = None, (0.5, False)
        for name, flags in candidates:
            union = np.count_nonzero(members | flags)
            score = (np.count_nonzero(members & flags) / union if union else 0.0,
                     label_from_name(name) is not None)
            if score > best_score:
                best, best_score = name, score
        names.append(best)
    return names
