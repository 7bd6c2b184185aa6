# SPDX-License-Identifier: GPL-3.0-or-later
"""The "Polycube" tab in the 3D view's sidebar: labels (legend, validation), settings,
last run, scrubbing. It only draws: what it shows is computed elsewhere and cached."""

import bpy

from .label_cache import label_summary
from .label_colours import LABEL_COLOURS, UNLABELLED_COLOUR, colours_shown, display_colour
from .label_operators import (
    OBJECT_OT_polycube_auto_label, OBJECT_OT_polycube_label_colours, OBJECT_OT_polycube_validate_labels)
from .operators import OBJECT_OT_polycube_deform
from .polycube_native import LABEL_NAMES
from .polycube_shape import has_polycube
from .remesh_operator import OBJECT_OT_polycube_remesh
from .report import advice, load_report, outcome
from .scrub import shown_iteration
from .shape_keys import polycube_keys
from .unconverged import OBJECT_OT_polycube_select_unconverged, unconverged_count
from .uv_operator import OBJECT_OT_polycube_uv
from .validation import KIND_NAMES, load_validation


class VIEW3D_PT_polycube(bpy.types.Panel):
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Polycube"
    bl_label = "Polycube"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.polycube
        obj = context.active_object
        if obj is None or obj.type != 'MESH':
            layout.label(text="Select a mesh object", icon='INFO')
        else:
            _draw_labels(layout.box(), obj, settings)

        settings.draw_settings(layout.column())
        button = layout.operator(OBJECT_OT_polycube_deform.bl_idname, icon='MESH_CUBE')
        settings.copy_settings_to(button)

        if obj is not None and obj.type == 'MESH':
            report = load_report(obj)
            if report is not None:
                _draw_report(layout.box(), report)
            _draw_scrub(layout, obj)
            if has_polycube(obj):
                _draw_uses(layout.box())


def _draw_labels(layout, obj, settings):
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
    else:
        source = summary.source.capitalize()
        layout.label(text=source, icon='FACESEL')
        # The legend: each label's colour in the viewport, and its faces.
        grid = layout.grid_flow(row_major=True, columns=2, even_columns=True, align=True)
        for name, count, colour in zip(LABEL_NAMES, summary.counts, LABEL_COLOURS):
            row = grid.row(align=True)
            row.template_node_socket(color=display_colour(colour))
            row.label(text=f"{name}: {count}")
        if summary.unlabelled:
            row = layout.row(align=True)
            row.template_node_socket(color=display_colour(UNLABELLED_COLOUR))
            row.label(text=f"Unlabelled: {summary.unlabelled} (nearest axis)")
        _draw_validation(layout, load_validation(obj, summary.digest))

    row = layout.row(align=True)
    button = row.operator(OBJECT_OT_polycube_auto_label.bl_idname, icon='SHADERFX')
    button.compactness = settings.compactness
    row.operator(OBJECT_OT_polycube_validate_labels.bl_idname, icon='CHECKMARK', text="Validate")
    row = layout.row(align=True)
    shown = colours_shown(obj.data)
    row.operator(OBJECT_OT_polycube_label_colours.bl_idname, icon='COLOR',
                 text="Refresh" if shown else "Show Colours").show = True
    if shown:
        row.operator(OBJECT_OT_polycube_label_colours.bl_idname, icon='X', text="Hide").show = False


def _draw_validation(layout, validation):
    if validation is None:
        layout.label(text="Labels not validated", icon='QUESTION')
        return
    if validation["valid"]:
        layout.label(text="Valid polycube labels", icon='CHECKMARK')
    else:
        layout.label(text=f"{validation['violations']} violations", icon='ERROR')
    for problem in validation.get("orientation", ()):
        layout.label(text=problem, icon='ERROR')
    rows = [("Charts", validation["charts"]), ("Corners", validation["corners"])]
    rows += [(KIND_NAMES.get(kind, kind), count) for kind, count in validation["kinds"].items()]
    _draw_rows(layout, rows)


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
        ("Labels", report["label_source"]),
        ("Shape keys", str(len(report.get("kept_iterations", ())))),
        ("Read", f"{seconds['read']:.3f} s"),
        ("Solve", f"{seconds['deform_call']:.3f} s"),
        ("Write", f"{seconds['write']:.3f} s"),
    )
    unconverged = unconverged_count(report)
    if unconverged is not None:
        rows += (("Unconverged faces", str(unconverged)),)
    if report.get("relabelled_faces_count"):
        rows += (("Relabelled faces", str(report["relabelled_faces_count"])),)
    if report.get("flat_iteration"):
        rows += (("Charts flat from", f"iteration {report['flat_iteration']}"),)
    _draw_rows(layout, rows)
    hint = advice(report)
    if hint:
        box = layout.box()
        box.label(text="Not a polycube yet", icon='ERROR')
        for line in hint:
            box.label(text=line)
    if unconverged:
        layout.operator(OBJECT_OT_polycube_select_unconverged.bl_idname, icon='RESTRICT_SELECT_OFF')


def _draw_uses(layout):
    layout.label(text="Use the Polycube", icon='MOD_REMESH')
    row = layout.row(align=True)
    row.operator(OBJECT_OT_polycube_uv.bl_idname, icon='UV')
    row.operator(OBJECT_OT_polycube_remesh.bl_idname, icon='MESH_GRID')


def _draw_rows(layout, rows):
    """(name, value) pairs as a two-column table."""
    column = layout.column(align=True)
    for name, value in rows:
        split = column.split(factor=0.6)
        split.label(text=name)
        split.label(text=str(value))


def _draw_scrub(layout, obj):
    keys = polycube_keys(obj)
    if not keys:
        return
    layout.prop(obj, "polycube_scrub", slider=True)
    layout.label(text=f"Showing iteration {shown_iteration(obj):.1f} of {keys[-1][0]}")
