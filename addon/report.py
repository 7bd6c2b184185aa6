# SPDX-License-Identifier: GPL-3.0-or-later
"""The last run's report, kept on the object as the custom property `polycube_report`."""

import numpy as np

REPORT_PROPERTY = "polycube_report"
# Blender 3.x ID properties have no booleans: these come back from 0/1.
_BOOLEAN_KEYS = ("converged", "stopped")


def store_report(obj, report):
    obj[REPORT_PROPERTY] = _plain(report)


def load_report(obj):
    stored = obj.get(REPORT_PROPERTY)
    if not hasattr(stored, "to_dict"):
        return None
    report = stored.to_dict()
    for key in _BOOLEAN_KEYS:
        if key in report:
            report[key] = bool(report[key])
    return report


def outcome(report):
    """How the run ended, in a word or two."""
    if report["stopped"]:
        return "stopped"
    return "converged" if report["converged"] else "not converged"


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
