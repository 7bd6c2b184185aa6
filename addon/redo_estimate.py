# SPDX-License-Identifier: GPL-3.0-or-later
"""What a change in the redo panel costs. Blender re-runs an operator there through
`execute`, synchronously: the modal run with its progress and Esc is for the first
run only. So the operators that take long keep how long their last run worked, and
their redo panel says it before the user changes anything."""

from bpy.props import FloatProperty


class RedoEstimate:
    """Mixin for operators: set `last_seconds` at the end of each run; draw_estimate in draw."""
    last_seconds: FloatProperty(
        name="Last Run Seconds", description="How long the last run worked (the redo panel's estimate)",
        default=-1.0, options={'HIDDEN', 'SKIP_SAVE'})

    def draw_estimate(self, layout):
        text = estimate_text(self.last_seconds)
        if text is not None:
            layout.label(text=text, icon='TIME')


def estimate_text(seconds):
    """The redo panel's line for a last run of `seconds`; None before any run."""
    if seconds < 0:
        return None
    return f"Each change runs it again: about {duration(seconds)}"


def duration(seconds):
    """0.4 s, 12 s, 2 min 5 s."""
    if seconds < 10:
        return f"{seconds:.1f} s"
    if seconds < 60:
        return f"{seconds:.0f} s"
    minutes, rest = divmod(round(seconds), 60)
    return f"{minutes} min {rest} s"
