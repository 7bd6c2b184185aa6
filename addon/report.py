# SPDX-License-Identifier: GPL-3.0-or-later
"""The last run's report, kept on the object as the custom property `polycube_report`."""

import numpy as np

REPORT_PROPERTY = "polycube_report"
# Face lists (the native report's `<key>` beside `<key>_count`: unconverged_faces, ...)
# are kept apart, so the sidebar, which reads the report at every redraw, does not
# convert them.
FACES_PROPERTY = "polycube_report_faces"
# The labels the solver ended with (it may relabel faces), one per face: what the
# polycube's uses (UV map, quad remesh) read its charts from.
LABELS_USED_PROPERTY = "polycube_labels_used"
# Blender 3.x ID properties have no booleans: these come back from 0/1.
_BOOLEAN_KEYS = ("converged", "stopped")


def store_report(obj, report):
    lists = {key for key, value in report.items()
             if f"{key}_count" in report and isinstance(value, (list, tuple, np.ndarray))}
    obj[REPORT_PROPERTY] = _plain({key: value for key, value in report.items() if key not in lists})
    obj[FACES_PROPERTY] = {key: np.asarray(report[key], dtype=np.int32) for key in lists}


def report_faces(obj, key):
    """A face list of the last run's report (ids of the object's faces), empty if none."""
    stored = obj.get(FACES_PROPERTY)
    values = stored.get(key) if hasattr(stored, "get") else None
    return np.array(values if values is not None else (), dtype=np.int64)


def store_labels_used(obj, labels):
    obj[LABELS_USED_PROPERTY] = np.asarray(labels, dtype=np.int32)


def load_labels_used(obj):
    """The labels of the last run, or None (a run before they were kept)."""
    stored = obj.get(LABELS_USED_PROPERTY)
    return np.array(stored, dtype=np.int32) if stored is not None else None


def load_report(obj):
    stored = obj.get(REPORT_PROPERTY)
    if not hasattr(stored, "to_dict"):
        return None
    report = stored.to_dict()
    for key in _BOOLEAN_KEYS:
        if key in report:
            report[key] = bool(report[key])
    return report


def work_seconds(report):
    """How long the run worked: reading (labels and refinement too), solving, writing;
    not the time the UI spent between the modal run's steps."""
    seconds = report["seconds"]
    return seconds["read"] + seconds["deform_call"] + seconds["write"]


def failure(name, verb, error):
    """One sentence: object `name` was not <verb> because of `error`."""
    message = str(error).strip().rstrip(".")
    if message[1:2].islower():
        message = message[0].lower() + message[1:]
    return f"'{name}' was not {verb}: {message}."


def outcome(report):
    """How the run ended, in a word or two."""
    if report.get("stalled_at"):
        return "no progress"
    if report["stopped"]:
        return "stopped"
    if report.get("failure"):
        return f"solver broke off ({report['failure']})"
    return "converged" if report["converged"] else "not converged"


def advice(report):
    """Short lines on what happened and what to try when the run did not become
    an exact polycube; empty when it did (or the user stopped it).

    The robust solver flattens the charts once it is close; an attempt is
    refused when it leaves folds or would crush too much of the model. Either
    way the labels ask for more than the mesh can give, and what to try depends
    on where they came from."""
    stalled = report.get("stalled_at")
    if report.get("converged") or (report.get("stopped") and not stalled):
        return []
    refused = [attempt for attempt in report.get("flatten_attempts") or () if not attempt.get("kept")]
    if not refused and not stalled:
        return []
    lines = []
    if stalled:
        lines.append(f"The mesh stopped moving after iteration {report.get('moved_until', 0)}; "
                     f"stopped at iteration {stalled}")
    if refused:
        last = refused[-1]
        collapsed = f"{100 * last.get('collapsed_area', 0.0):.0f}% of the surface"
        if last.get("folds_left"):
            lines.append(f"Flat charts would leave {last['folds_left']} folded faces "
                         f"(and collapse {collapsed})")
        else:
            lines.append(f"Flat charts would collapse {collapsed}")
    if report.get("labels_automatic"):
        lines.append("The automatic labels ask too much here: relabel the unconverged faces "
                     "(Edit Mode, Assign Label), or try another Detail")
    elif report.get("labelled_faces", 1) == 0:
        lines.append("Every face took its nearest axis: try Auto Label")
    else:
        lines.append("Try Auto Label, or relabel the unconverged faces")
    return lines


def _plain(value):
    # ID properties take Python scalars, strings, lists and dicts, not numpy types.
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return int(value)
    if isinstance(value, (np.integer, int)):
        return int(value)
    if isinstance(value, (np.floating, float)):
        return float(value)
    return str(value)
