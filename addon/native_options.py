# SPDX-License-Identifier: GPL-3.0-or-later
"""What the native module offers, read from the module itself: its solver
variants and the defaults of its keyword arguments.

A newer module with another variant (or another default) then shows up in the
operator and the sidebar without a change here.
"""

import ast
import re

import numpy as np

from . import polycube_native

# Offered when the module's answer cannot be read; a name it refuses is then
# reported by the operator like any other bad input.
_FALLBACK_VARIANTS = ("robust", "fixed", "current")
_DESCRIPTIONS = {
    "robust": "Fold-free steps: no face turns over; faces that cannot reach their axis are listed",
    "fixed": "Cotangent Laplacian of the input mesh, factorised once: fast",
    "current": "Laplacian of the current mesh, refactorised every iteration (as in the paper)",
}


def keyword_default(function, name, fallback):
    """The default of a keyword argument, from the signature pybind11 writes atop the docstring."""
    match = re.search(rf"\b{name}: \w+ = ('[^']*'|[-+.\w]+)", function.__doc__ or "")
    if match is None:
        return fallback
    try:
        return type(fallback)(ast.literal_eval(match.group(1)))
    except (ValueError, SyntaxError):
        return fallback


def _solver_variants():
    # An unknown name on an empty mesh fails at once, naming the variants the module knows.
    empty = np.empty((0, 3)), np.empty(0, np.int32), np.empty(0, np.int32), np.empty(0, np.int32)
    try:
        polycube_native.deform(*empty, iterations=1, variant="?")
    except ValueError as error:
        names = re.findall(r"'(\w+)'", str(error).partition(" use ")[2])
        if names:
            return tuple(names)
    return _FALLBACK_VARIANTS


VARIANTS = _solver_variants()
DEFAULT_VARIANT = keyword_default(polycube_native.deform, "variant", VARIANTS[0])
if DEFAULT_VARIANT not in VARIANTS:
    DEFAULT_VARIANT = VARIANTS[0]
DEFAULT_COMPACTNESS = keyword_default(polycube_native.auto_labels, "compactness", 0.3)


def variant_items():
    """EnumProperty items, one per variant, in the module's order."""
    return tuple((name.upper(), name.capitalize(),
                  _DESCRIPTIONS.get(name, f"The native solver's '{name}' variant"))
                 for name in VARIANTS)
