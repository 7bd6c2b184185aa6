# SPDX-License-Identifier: GPL-3.0-or-later
"""What the native module offers: its solver variants and defaults, so a newer
module with another variant or default shows up in the operator and the
sidebar without a change here."""

from . import polycube_native

VARIANTS = polycube_native.VARIANTS
DEFAULT_VARIANT = polycube_native.DEFAULT_VARIANT
DEFAULT_DETAIL = polycube_native.DEFAULT_DETAIL
MAX_REFINE_LEVELS = polycube_native.MAX_REFINE_LEVELS
DEFAULT_COARSE_TRIANGLES = polycube_native.DEFAULT_COARSE_TRIANGLES

_DESCRIPTIONS = {
    "robust": "Fold-free steps: no face turns over; faces that cannot reach their axis are listed",
    "fixed": "Cotangent Laplacian of the input mesh, factorised once: fast",
    "current": "Laplacian of the current mesh, refactorised every iteration (as in the paper)",
}


def variant_items():
    """EnumProperty items, one per variant, in the module's order."""
    return tuple((name.upper(), name.capitalize(),
                  _DESCRIPTIONS.get(name, f"The native solver's '{name}' variant"))
                 for name in VARIANTS)
