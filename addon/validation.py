# SPDX-License-Identifier: GPL-3.0-or-later
"""Labels checked against the polycube conditions (docs/design.md section 3): the
native validator's answer in words, and its figures kept on the object for the
sidebar (which must not compute them while it draws).

The figures carry a digest of the labels they were made from, so the sidebar
can tell when the labels changed since.
"""

import hashlib

import numpy as np

from .polycube_native import orientation, validate_labels

VALIDATION_PROPERTY = "polycube_validation"

# Per violation kind: a short name (sidebar), and (one, several) for the summary sentence.
KIND_NAMES = {
    "too_few_neighbours": "Fewer than 4 neighbours",
    "opposite_neighbours": "Opposite neighbours",
    "corner_too_many_charts": "Corners of 4+ charts",
    "reversed_chart": "Charts facing away",
    "turning_point": "Boundaries turning back",
    "squeezed_faces": "Squeezed faces",
}
_KIND_WORDS = {
    "too_few_neighbours": ("chart touches fewer than four others",
                           "charts touch fewer than four others"),
    "opposite_neighbours": ("chart borders a chart of the opposite label",
                            "charts border a chart of the opposite label"),
    "corner_too_many_charts": ("corner joins more than three charts",
                               "corners join more than three charts"),
    "reversed_chart": ("chart faces away from its axis", "charts face away from their axes"),
    "turning_point": ("chart boundary turns back along its polycube edge",
                      "chart boundaries turn back along their polycube edges"),
    "squeezed_faces": ("chart has faces flat charts squeeze onto a line",
                       "charts have faces flat charts squeeze onto a line"),
}


def labels_digest(values):
    """A short fingerprint of a labelling."""
    return hashlib.blake2b(np.ascontiguousarray(values, dtype=np.int32).tobytes(), digest_size=8).hexdigest()


def validate(obj, mesh, values):
    """The validator's answer for labels `values` of MeshArrays `mesh`, with the
    winding's problems as sentences under "orientation"; its figures kept on the object."""
    result = validate_labels(mesh.vertices, mesh.face_indices, mesh.face_sizes, values)
    problems = _orientation_problems(orientation(mesh.vertices, mesh.face_indices, mesh.face_sizes, values))
    result["orientation"] = [sentence for _, sentence in problems]
    obj[VALIDATION_PROPERTY] = dict(
        digest=labels_digest(values), valid=int(result["valid"]), realisable=int(result["realisable"]),
        charts=result["charts"],
        boundaries=result["boundaries"], corners=result["corners"],
        unlabelled_faces=result["unlabelled_faces"], violations=len(result["violations"]),
        kinds=_kind_counts(result), orientation=[short for short, _ in problems])
    return result


def _orientation_problems(found):
    """Labels mean something against outward normals only: what stands in the way,
    as (a few words for the sidebar, a sentence for the info log)."""
    problems = []
    if not found["orientable"]:
        problems.append(("Not orientable",
                         "the mesh is not orientable, so some faces face inward whatever is done"))
    elif not found["consistent"]:
        problems.append(("Inconsistent winding",
                         f"neighbouring faces are wound in opposite directions along "
                         f"{_count(found['inconsistent_edges'], 'edge')} "
                         f"(Mesh > Normals > Recalculate Outside)"))
    if found["inward_components"]:
        parts = found["inward_components"]
        problems.append(("Wound inward",
                         f"{_count(parts, 'closed part')} of the mesh {'is' if parts == 1 else 'are'} "
                         f"wound inward (Mesh > Normals > Recalculate Outside)"))
    if found.get("labels_opposite"):
        problems.append(("Labels for the opposite winding",
                         f"{found['area_against_labels']:.0%} of the area faces away from its label: "
                         f"the labels look made for the opposite winding"))
    return problems


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
    if result["realisable"]:
        winding = " but the winding is not outward everywhere (see the info log)" if result.get("orientation") else ""
        return f"'{name}': the labels are a valid polycube ({figures}){winding}."
    parts = [f"{count} {_KIND_WORDS.get(kind, (kind, kind))[count > 1]}"
             for kind, count in _kind_counts(result).items()]
    selected = f", {faces_selected} faces selected" if faces_selected is not None else ""
    if result["valid"]:
        return (f"'{name}': the labels are a valid polycube, but flat charts would collapse faces: "
                f"{', '.join(parts)} ({figures}{selected}).")
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
        elif v["kind"] == "reversed_chart":
            lines.append(f"{chart} faces away from its axis: no polycube turns it without turning "
                         f"the surface inside out")
        elif v["kind"] == "turning_point":
            lines.append(f"{chart} meets chart {others} along a boundary that turns back along their "
                         f"polycube edge: the faces where it turns back would collapse")
        elif v["kind"] == "squeezed_faces":
            lines.append(f"{chart}: its selected faces lie between planes of one other chart and "
                         f"would collapse onto a line")
        else:
            lines.append(f"{chart}: {v['kind']}")
    return lines


def _kind_counts(result):
    counts = {}
    for violation in result["violations"]:
        counts[violation["kind"]] = counts.get(violation["kind"], 0) + 1
    return counts


def _count(number, noun):
    return f"{number} {noun}{'' if number == 1 else 's'}"
