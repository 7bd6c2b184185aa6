# SPDX-License-Identifier: GPL-3.0-or-later
"""Label counts for the sidebar, read once per change rather than on every redraw."""

from typing import NamedTuple

import bpy
from bpy.app.handlers import persistent

from .labels import label_counts, read_labels
from .validation import labels_digest


class LabelSummary(NamedTuple):
    source: str
    counts: list        # faces per label, LABEL_NAMES order
    unlabelled: int
    error: str          # why the labels cannot be used, or None
    digest: str         # fingerprint of the labels (validation.labels_digest), or None


_summaries = {}


def label_summary(obj):
    # Renaming a face map or an attribute triggers no depsgraph update: key on names too.
    mesh = obj.data
    key = (obj.as_pointer(), mesh.as_pointer(), mesh.is_editmode, len(mesh.polygons),
           tuple(face_map.name for face_map in getattr(obj, "face_maps", ())),
           tuple(attribute.name for attribute in mesh.attributes))
    summary = _summaries.get(key)
    if summary is None:
        try:
            labels = read_labels(obj)
            summary = LabelSummary(labels.source, *label_counts(labels.values), None,
                                   labels_digest(labels.values))
        except (ValueError, RuntimeError, ReferenceError) as error:
            # The sidebar draws this instead of going blank.
            summary = LabelSummary(None, None, None, str(error), None)
        _summaries[key] = summary
    return summary


def forget():
    """Read the labels again at the next draw (an operator changed them)."""
    _summaries.clear()


@persistent
def _forget_on_edit(scene, depsgraph):
    if any(isinstance(update.id, (bpy.types.Mesh, bpy.types.Object)) for update in depsgraph.updates):
        _summaries.clear()


@persistent
def _forget_all(*_args):
    _summaries.clear()


_HANDLERS = (
    (bpy.app.handlers.depsgraph_update_post, _forget_on_edit),
    (bpy.app.handlers.load_post, _forget_all),
    (bpy.app.handlers.undo_post, _forget_all),
    (bpy.app.handlers.redo_post, _forget_all),
)


def register():
    for handlers, handler in _HANDLERS:
        handlers.append(handler)


def unregister():
    for handlers, handler in _HANDLERS:
        if handler in handlers:
            handlers.remove(handler)
    _summaries.clear()
