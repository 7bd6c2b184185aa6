# SPDX-License-Identifier: GPL-3.0-or-later
"""Labels checked against the polycube conditions (DESIGN.md section 3): the
native validator's answer in words, and its figures kept on the object for the
sidebar (which must not compute them while it draws).

The figures carry a digest of the labels they were made from, so the sidebar
can tell when the labels changed since.
"""

import hashlib

import numpy as np

from .polycube_native import validate_labels

VALIDATION_PROPERTY = "polycube_validation"

# Per violation kind: (one, several) for the summary sentence.
_KIND_WORDS = {
    "too_few_neighbours": ("chart touches fewer than four others",
                           "charts touch fewer than four others"),
    "opposite_neighbours": ("chart borders a chart of the opposite label",
                            "charts border a chart of the opposite label"),
    "corner_too_many_charts": ("corner joins more than three charts",
                               "corners join more than three charts"),
}


def labels_digest(values):
    """A short fingerprint of a labelling."""
    return hashlib.blake2b(np.ascontiguousarray(values, dtype=np.int32).tobytes(), digest_size=8).hexdigest()


def validate(obj, mesh, values):
    """The validator's answer for labels `values` of MeshArrays `mesh`; kept on the object."""
    result = validate_labels(mesh.vertices, mesh.face_indices, mesh.face_sizes, values)
    kinds = {}
    for violation in result["violations"]:
        kinds[violation["kind"]] = kinds.get(violation["kind"], 0) + 1
    obj[VALIDATION_PROPERTY] = dict(
        digest=labels_digest(values), valid=int(result["valid"]), charts=result["charts"],
        boundaries=result["boundaries"], corners=result["corners"],
        unlabelled_faces=result["unlabelled_faces"], violations=len(result["violations"]), kinds=kinds)
    return result


def load_validation(obj, digest):
    """The figures kept by the last validation, if made from labels with this digest."""
    stored = obj.get(VALIDATION_PROPERTY)
    if not hasattr(stored, "to_dict") or stored.get("digest") != digest:
        return None
    return stored.to_dict()


def offending_faces(result):
    """Every face some violation names, ascending."""
    faces = [np.asarray(violation["faces"], dtype=np.int64) for violation in result["violations"]]
    return np.unique(np.concatenate(faces)) if faces else np.empty(0, dtype=np.int64)


def summary(name, result, faces_selected=None):
    """One sentence on the labels of object `name`."""
    figures = f"{result['charts']} charts, {result['corners']} corners"
    if result["valid"]:
        return f"'{name}': the labels are a valid polycube ({figures})."
    counts = {}
    for violation in result["violations"]:
        counts[violation["kind"]] = counts.get(violation["kind"], 0) + 1
    parts = [f"{count} {_KIND_WORDS.get(kind, (kind, kind))[count > 1]}" for kind, count in counts.items()]
    selected = f", {faces_selected} faces selected" if faces_selected is not None else ""
    return f"'{name}': the labels are not a valid polycube: {', '.join(parts)} ({figures}{selected})."


def details(result):
    """One line per violation, for the info log."""
    lines = []
    for v in result["violations"]:
        chart = f"chart {v['chart']} ({v['label_name']}, {_count(len(v['faces']), 'face')})"
        others = ", ".join(str(other) for other in v["others"])
        if v["kind"] == "too_few_neighbours":
            lines.append(f"{chart} touches {_count(len(v['others']), 'other chart')} ({others}); "
                         f"it needs four")
        elif v["kind"] == "opposite_neighbours":
            lines.append(f"{chart} borders chart {others} of the opposite label")
        elif v["kind"] == "corner_too_many_charts":
            lines.append(f"vertex {v['vertex']}: {chart} meets charts {others} at one corner")
        else:
            lines.append(f"{chart}: {v['kind']}")
    return lines


def _count(number, noun):
    return f"{number} {noun}{'' if number == 1 else 's'}"
