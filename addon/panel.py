# SPDX-License-Identifier: GPL-3.0-or-later
"""The "Polycube" tab in the 3D view's sidebar: labels, settings, last run, scrubbing."""

import bpy

from .label_cache import label_summary
from .labels import NO_LABELS
from .operators import OBJECT_OT_polycube_deform
from .polycube_native import LABEL_NAMES
from .report import load_report, outcome
from .scrub import shown_iteration
from .shape_keys import polycube_keys


class VIEW3D_PT_polycube(bpy.types.Panel):
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Polycube"
    bl_label = "Polycube"

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        if obj is None or obj.type != 'MESH':
            layout.label(text="Select a mesh object", icon='INFO')
        else:
            _draw_labels(layout.box(), obj)

        settings = context.scene.polycube
        settings.draw_settings(layout.column())
        button = layout.operator(OBJECT_OT_polycube_deform.bl_idname, icon='MESH_CUBE')
        settings.copy_settings_to(button)

        if obj is not None and obj.type == 'MESH':
            report = load_report(obj)
            if report is not None:
                _draw_report(layout.box(), report)
            _draw_scrub(layout, obj)


def _draw_labels(layout, obj):
    summary = label_summary(obj)
    if summary.error is not None:
        layout.label(text="Labels cannot be used:", icon='ERROR')
        # The sentence is long: wrap it over a few lines.
        words, line = summary.error.split(), ""
        for word in words:
            if len(line) + len(word) > 38:
                layout.label(text=line)
                line = ""
            line += word + " "
        layout.label(text=line)
        return
    source = "None: nearest axis" if summary.source == NO_LABELS else summary.source.capitalize()
    layout.label(text=source, icon='FACESEL')
    grid = layout.grid_flow(row_major=True, columns=2, even_columns=True, align=True)
    for name, count in zip(LABEL_NAMES, summary.counts):
        grid.label(text=f"{name}: {count}")
    if summary.unlabelled:
        layout.label(text=f"Unlabelled: {summary.unlabelled} (nearest axis)")


def _draw_report(layout, report):
    layout.label(text="Last Run", icon='INFO')
    seconds = report["seconds"]
    rows = (
        ("Iterations", f"{report['iterations']}, {outcome(report)}"),
        ("Max deviation", f"{report['normal_deviation_max_deg']:.3f}°"),
        ("Mean deviation", f"{report['normal_deviation_mean_deg']:.3f}°"),
        ("Flipped faces", str(report["flipped_faces"])),
        ("Collapsed faces", str(report["collapsed_faces"])),
        ("Edge error", f"{report['edge_error']:.4f}"),
        ("Area error", f"{report['area_error']:.4f}"),
        ("Unlabelled faces", str(report["unlabelled_faces"])),
        ("Shape keys", str(len(report.get("kept_iterations", ())))),
        ("Read", f"{seconds['read']:.3f} s"),
        ("Solve", f"{seconds['deform_call']:.3f} s"),
        ("Write", f"{seconds['write']:.3f} s"),
    )
    column = layout.column(align=True)
    for name, value in rows:
        split = column.split(factor=0.6)
        split.label(text=name)
        split.label(text=value)


def _draw_scrub(layout, obj):
    keys = polycube_keys(obj)
    if not keys:
        return
    layout.prop(obj, "polycube_scrub", slider=True)
    layout.label(text=f"Showing iteration {shown_iteration(obj):.1f} of {keys[-1][0]}")
