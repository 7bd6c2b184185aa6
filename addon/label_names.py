# SPDX-License-Identifier: GPL-3.0-or-later
"""Which face-map names stand for which polycube label (docs/design.md section 3)."""

from .polycube_native import LABEL_NAMES


def _spellings(label_name):
    sign, axis = label_name[0], label_name[1:]
    if sign == "+":
        return ("+" + axis, axis + "+", "P" + axis, "POS_" + axis)
    return ("-" + axis, axis + "-", "N" + axis, "NEG_" + axis)


_LABEL_BY_SPELLING = {
    spelling: value
    for value, name in enumerate(LABEL_NAMES)
    for spelling in _spellings(name)
}

ACCEPTED_SPELLINGS = (
    "+X, X+, PX or POS_X (-X, X-, NX or NEG_X for the negative side, "
    "likewise for Y and Z, in any case)"
)


def label_from_name(name):
    """The label value (index into LABEL_NAMES) a face-map name stands for, or None."""
    return _LABEL_BY_SPELLING.get(name.strip().upper())
