# SPDX-License-Identifier: GPL-3.0-or-later
"""The labels a deformation uses: stored on the object, automatic, or both
(DeformSettings.label_source)."""

import numpy as np

from .labels import Labels, read_labels
from .polycube_native import auto_labels
from .validation import labels_digest

AUTOMATIC = "automatic"
# Mesh property: the digest of the labels Auto Label wrote last, so that a run can
# tell labels from Auto Label (advice differs) from the user's.
AUTO_LABELS_PROPERTY = "polycube_auto_labels"


def mark_automatic(mesh, values):
    mesh[AUTO_LABELS_PROPERTY] = labels_digest(values)


def is_automatic(obj, labels):
    """Whether the labels of a run came from the labeller (this run's or Auto Label's)."""
    return labels.source.startswith(AUTOMATIC) or "automatic where unlabelled" in labels.source or \
        obj.data.get(AUTO_LABELS_PROPERTY) == labels_digest(labels.values)


def stored_labels(obj, source):
    """The stored Labels a run starts from (main thread); None when `source` labels every
    face automatically. ValueError if the stored ones are junk."""
    return None if source == 'AUTO' else read_labels(obj)


def labels_for_run(stored, mesh, source, options):
    """The labels a run uses: `stored` (from stored_labels), completed by the labeller
    where `source` asks. `mesh`: the object's MeshArrays; `options`: the labeller's
    keyword arguments (settings.label_options). Touches no Blender data: may run on a
    worker thread."""
    if stored is None:
        return Labels(automatic_labels(mesh, options), AUTOMATIC)
    unlabelled = stored.values < 0
    if source == 'STORED' or not unlabelled.any():
        return stored
    if unlabelled.all():
        return Labels(automatic_labels(mesh, options), AUTOMATIC)
    values = np.where(unlabelled, automatic_labels(mesh, options), stored.values).astype(np.int32)
    return Labels(values, f"{stored.source}, automatic where unlabelled")


def automatic_labels(mesh, options):
    """The labeller's labels for MeshArrays `mesh`; `options` as settings.label_options gives.
    Touches no Blender data: may run on a worker thread."""
    return np.asarray(auto_labels(mesh.vertices, mesh.face_indices, mesh.face_sizes, **options),
                      dtype=np.int32)

