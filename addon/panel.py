# SPDX-License-Identifier: GPL-3.0-or-later
"""The "Polycube" tab in the 3D view's sidebar, in Object and Edit Mode: the scrub
slider on top, then sub-panels Labels (legend, validation, Assign Label in Edit
Mode), Deform (settings, button, what to try next), Use the Polycube (UV map,
remesh) and Last Run (figures, closed by default). It only draws: what it shows is computed elsewhere and cached."""

import bpy

from .label_assign import draw_label_buttons
from .label_cache import label_summary
from .label_colours import LABEL_COLOURS, colours_shown, display_colour
from .label_operators import (
    OBJECT_OT_polycube_auto_label, OBJECT_OT_polycube_label_colours, OBJECT_OT_polycube_validate_labels)
from .operators import OBJECT_OT_polycube_deform
from .polycube_native import LABEL_NAMES
from .polycube_shape import has_polycube
from .remesh_operator import OBJECT_OT_polycube_remesh
from .report import advice, load_report, outcome
from .scrub import shown_iteration
from .settings import label_options
from .shape_keys import polycube_keys
from .sidebar import SidebarTab
from .unconverged import OBJECT_OT_polycube_select_unconverged, unconverged_count
from .uv_operator import OBJECT_OT_polycube_uv
from .validation import KIND_NAMES, load_validation


def _mesh(context):
    obj = context.active_object
    return obj if obj is not None and obj.type == 'MESH' else None


class VIEW3D_PT_polycube(SidebarTab, bpy.types.Panel):
    bl_label = "Polycube"

    def draw(self, context):
        layout = self.layout
        obj = _mesh(context)
        if obj is None:
            layout.label(text="Select a mesh object", icon='INFO')
            return
        keys = polycube_keys(obj)
        if keys:
            layout.prop(obj, "polycube_scrub", slider=True)
            layout.label(text=f"Iteration {shown_iteration(obj):.1f} of {keys[-1][0]}")
        else:
            layout.label(text="Not deformed yet")


class _SubPanel(SidebarTab):
    bl_parent_id = "VIEW3D_PT_polycube"

    @classmethod
    def poll(cls, context):
        return _mesh(context) is not None


class VIEW3D_PT_polycube_labels(_SubPanel, bpy.types.Panel):
    bl_label = "Labels"

    def draw(self, context):
        layout = self.layout
        obj = _mesh(context)
        settings = context.scene.polycube
        summary = label_summary(obj)
        if summary.error is not None:
            layout.label(text="Labels cannot be used:", icon='ERROR')
            wrap(layout, context, summary.error)
        else:
            layout.label(text=summary.source.capitalize(), icon='FACESEL')
            # The legend: each label's color in the viewport, and its faces.
            grid = layout.grid_flow(row_major=True, columns=2, even_columns=True, align=True)
            for name, count, colour in zip(LABEL_NAMES, summary.counts, LABEL_COLOURS):
                row = grid.row(align=True)
                row.template_node_socket(color=display_colour(colour))
                row.label(text=f"{name}: {count}")
            if summary.unlabelled:
                # Colors show them pale, in the color of the axis the solver gives them.
                wrap(layout, context, f"Unlabelled: {summary.unlabelled}, pale: nearest axis")
            _draw_validation(layout, context, load_validation(obj, summary.digest))

        if context.mode == 'EDIT_MESH':
            layout.label(text="Assign (Shift Alt L):")
            draw_label_buttons(layout.column(align=True))
        row = layout.row(align=True)
        button = row.operator(OBJECT_OT_polycube_auto_label.bl_idname, icon='SHADERFX')
        for name, value in label_options(settings).items():
            setattr(button, name, value)
        row.operator(OBJECT_OT_polycube_validate_labels.bl_idname, icon='CHECKMARK', text="Validate")
        row = layout.row(align=True)
        shown = colours_shown(obj.data)
        row.operator(OBJECT_OT_polycube_label_colours.bl_idname, icon='COLOR',
                     text="Refresh" if shown else "Show Colors").show = True
        if shown:
            row.operator(OBJECT_OT_polycube_label_colours.bl_idname, icon='X', text="Hide").show = False


class VIEW3D_PT_polycube_deform(_SubPanel, bpy.types.Panel):
    bl_label = "Deform"

    @classmethod
    def poll(cls, context):
        return True  # the button deforms every selected mesh, active or not

    def draw(self, context):
        layout = self.layout
        settings = context.scene.polycube
        settings.draw_settings(layout.column())
        button = layout.operator(OBJECT_OT_polycube_deform.bl_idname, icon='MESH_CUBE')
        settings.copy_settings_to(button)
        obj = _mesh(context)
        report = load_report(obj) if obj is not None else None
        if report is None:
            return
        layout.label(text=f"Last run: {outcome(report)}, {report['iterations']} iterations")
        hint = advice(report)
        if hint:
            box = layout.box()
            box.label(text="Not a polycube yet", icon='ERROR')
            for line in hint:
                wrap(box, context, line)
        if unconverged_count(report):
            layout.operator(OBJECT_OT_polycube_select_unconverged.bl_idname, icon='RESTRICT_SELECT_OFF')


class VIEW3D_PT_polycube_last_run(_SubPanel, bpy.types.Panel):
    bl_label = "Last Run"
    bl_options = {'DEFAULT_CLOSED'}

    @classmethod
    def poll(cls, context):
        obj = _mesh(context)
        return obj is not None and load_report(obj) is not None

    def draw(self, context):
        report = load_report(_mesh(context))
        seconds = report["seconds"]
        rows = (
            ("Iterations", str(report["iterations"])),
            ("Max deviation", f"{report['normal_deviation_max_deg']:.3f}°"),
            ("Mean deviation", f"{report['normal_deviation_mean_deg']:.3f}°"),
            ("Flipped faces", str(report["flipped_faces"])),
            ("Collapsed faces", str(report["collapsed_faces"])),
            ("Edge error", f"{report['edge_error']:.4f}"),
            ("Area error", f"{report['area_error']:.4f}"),
            ("Largest area ratio", f"{report.get('max_area_ratio', 0.0):.1f}"),
            ("Unlabelled", str(report["unlabelled_faces"])),
            ("Shape keys", str(len(report.get("kept_iterations", ())))),
            ("Read", f"{seconds['read']:.3f} s"),
            ("Solve", f"{seconds['deform_call']:.3f} s"),
            ("Write", f"{seconds['write']:.3f} s"),
        )
        unconverged = unconverged_count(report)
        if unconverged is not None:
            rows += (("Unconverged", str(unconverged)),)
        if report.get("relabelled_faces_count"):
            rows += (("Relabelled", str(report["relabelled_faces_count"])),)
        if report.get("flat_iteration"):
            rows += (("Flat from", f"iteration {report['flat_iteration']}"),)
        if report.get("polish_steps"):
            rows += (("Polished", f"{report['polish_steps']} steps"),)
        if report.get("last_resort"):
            # docs/design.md section 2.6, stage 9: the labels flattened only
            # by collapsing more than a first run accepts.
            rows += (("Flattened", "at the last resort"),)
        layout = self.layout
        _draw_rows(layout, rows)
        layout.label(text="Labels:")
        wrap(layout, context, report["label_source"])


class VIEW3D_PT_polycube_use(_SubPanel, bpy.types.Panel):
    bl_label = "Use the Polycube"

    @classmethod
    def poll(cls, context):
        obj = _mesh(context)
        return obj is not None and has_polycube(obj)

    def draw(self, context):
        column = self.layout.column(align=True)
        column.operator(OBJECT_OT_polycube_uv.bl_idname, icon='UV')
        column.operator(OBJECT_OT_polycube_remesh.bl_idname, icon='MESH_GRID')


def _draw_validation(layout, context, validation):
    if validation is None:
        layout.label(text="Not validated", icon='QUESTION')
        return
    if validation["valid"]:
        layout.label(text="Valid polycube labels", icon='CHECKMARK')
    else:
        layout.label(text=f"{validation['violations']} violations", icon='ERROR')
    for problem in validation.get("orientation", ()):
        wrap(layout, context, problem, icon='ERROR')
    rows = [("Charts", validation["charts"]), ("Corners", validation["corners"])]
    rows += [(KIND_NAMES.get(kind, kind), count) for kind, count in validation["kinds"].items()]
    _draw_rows(layout, rows)


def _draw_rows(layout, rows):
    """(name, value) pairs as a two-column table."""
    column = layout.column(align=True)
    for name, value in rows:
        split = column.split(factor=0.55)
        split.label(text=name)
        split.label(text=str(value))


def wrap(layout, context, text, icon='NONE'):
    """A sentence over as many lines as the sidebar's width needs."""
    region = context.region
    scale = context.preferences.system.ui_scale
    # About 7 pixels a character at scale 1 in Blender's default font; margins aside.
    width = max(16, int(((region.width if region is not None else 300) - 40) / (7 * scale)))
    line = ""
    for word in text.split():
        if line and len(line) + 1 + len(word) > width:
            layout.label(text=line, icon=icon)
            icon, line = 'BLANK1' if icon != 'NONE' else 'NONE', ""
        line = f"{line} {word}" if line else word
    layout.label(text=line, icon=icon)


CLASSES = (VIEW3D_PT_polycube, VIEW3D_PT_polycube_labels, VIEW3D_PT_polycube_deform,
           VIEW3D_PT_polycube_use, VIEW3D_PT_polycube_last_run)
