# SPDX-License-Identifier: GPL-3.0-or-later
"""Labels as face colours: the palette (viewport, sidebar legend, preview renders)
and the colour attribute that shows it.

A face without a label is painted in a pale version of its nearest axis's colour:
the axis the solver gives it (docs/design.md section 3), shown as not assigned.

The add-on writes one colour attribute of its own, `polycube_label_colour`, and
never changes the user's: showing makes ours the active one (the one the
viewport's Attribute colour displays) and remembers which was active before;
hiding removes ours and makes that one active again.
"""

import numpy as np

from .mesh_arrays import face_of_corner, read_mesh_arrays
from .polycube_native import nearest_labels

# +X, -X, +Y, -Y, +Z, -Z: one hue per axis, darker for the negative side (linear RGBA).
LABEL_COLOURS = np.array([
    (0.90, 0.25, 0.20, 1.0), (0.45, 0.10, 0.08, 1.0),
    (0.35, 0.75, 0.25, 1.0), (0.12, 0.38, 0.10, 1.0),
    (0.25, 0.45, 0.95, 1.0), (0.10, 0.18, 0.50, 1.0),
], dtype=np.float32)
# Unlabelled faces: their nearest axis's colour, more than half way to white.
NEAREST_COLOURS = np.hstack([0.4 * LABEL_COLOURS[:, :3] + 0.6, LABEL_COLOURS[:, 3:]]).astype(np.float32)
COLOUR_ATTRIBUTE = "polycube_label_colour"
_SHOWN_OVER = "polycube_colour_shown_over"  # mesh property: the active colour attribute before ours


def colour_faces(mesh, labels, name=COLOUR_ATTRIBUTE):
    """Write (or overwrite) a corner colour attribute holding each face's label colour (pale
    nearest axis where unlabelled); make it active. ValueError if an unlabelled face's
    nearest axis cannot be told (a mesh the solver refuses)."""
    attribute = mesh.color_attributes.get(name)
    if attribute is not None and (attribute.domain, attribute.data_type) != ('CORNER', 'BYTE_COLOR'):
        mesh.color_attributes.remove(attribute)
        attribute = None
    if attribute is None:
        attribute = mesh.color_attributes.new(name, 'BYTE_COLOR', 'CORNER')
    labels = np.asarray(labels)
    unlabelled = labels < 0
    if unlabelled.any():
        nearest = np.asarray(nearest_labels(*read_mesh_arrays(mesh)))
        labels = np.where(unlabelled, nearest + len(LABEL_COLOURS), labels)
    palette = np.vstack([LABEL_COLOURS, NEAREST_COLOURS])
    attribute.data.foreach_set("color", palette[labels[face_of_corner(mesh)]].ravel())
    active = mesh.color_attributes.active_color
    if active is not None and active.name != name:
        mesh[_SHOWN_OVER] = active.name
    mesh.color_attributes.active_color = mesh.color_attributes[name]


def display_colour(rgba):
    """A palette colour as the screen shows it (sRGB), for the sidebar legend."""
    rgb = np.asarray(rgba[:3], dtype=np.float64)
    srgb = np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * rgb ** (1 / 2.4) - 0.055)
    return (*srgb.tolist(), float(rgba[3]))


def nearest_axes(normals):
    """The nearest axis label of each (n, 3) normal, as the solver picks it (the first
    of equally near axes)."""
    normals = np.asarray(normals, dtype=np.float64).reshape(-1, 3)
    axis = np.argmax(np.abs(normals), axis=1)
    return 2 * axis + (normals[np.arange(len(normals)), axis] < 0)


def colours_shown(mesh):
    return COLOUR_ATTRIBUTE in mesh.color_attributes


def hide_colours(mesh):
    """Remove our colour attribute; the one active before it is active again."""
    attribute = mesh.color_attributes.get(COLOUR_ATTRIBUTE)
    if attribute is not None:
        mesh.color_attributes.remove(attribute)
    previous = mesh.color_attributes.get(mesh.pop(_SHOWN_OVER, ""))
    if previous is not None:
        mesh.color_attributes.active_color = previous
