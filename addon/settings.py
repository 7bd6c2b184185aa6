# SPDX-License-Identifier: GPL-3.0-or-later
"""The settings, declared once for the operators and the panel.

The operators inherit them (redo panel); the scene keeps a copy
(`scene.polycube`) so the sidebar remembers what the user chose between runs.
"""

from collections import namedtuple

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty

from .native_options import DEFAULT_COARSE_TRIANGLES, DEFAULT_DETAIL, DEFAULT_VARIANT, MAX_REFINE_LEVELS, variant_items


def _setting_names(cls):
    """The properties a settings class declares, its mixins' first."""
    return tuple(name for base in reversed(cls.__mro__)
                 for name in base.__dict__.get("__annotations__", {}))


class LabelSettings:
    """The automatic labeller's options, each named as the native auto_labels'
    keyword argument it is passed to (label_options)."""
    detail: FloatProperty(
        name="Detail",
        description="Automatic labels: 0 gives a few large charts (a polycube you would sketch), "
                    "1 many small ones that follow every feature",
        default=DEFAULT_DETAIL, min=0.0, max=1.0, precision=2, subtype='FACTOR')


def label_options(settings):
    """The keyword arguments of polycube_native.auto_labels from any settings
    object (operator, scene, RunSettings): every LabelSettings property."""
    return {name: getattr(settings, name) for name in _setting_names(LabelSettings)}


class DeformSettings(LabelSettings):
    label_source: EnumProperty(
        name="Labels", description="Where each face's label comes from",
        items=(
            ('STORED', "Stored Labels",
             "The object's face maps or polycube_label attribute; unlabelled faces take their nearest axis"),
            ('AUTO', "Automatic Labels", "Label every face automatically, ignoring the stored labels"),
            ('AUTO_UNLABELLED', "Auto Where Unlabelled",
             "Keep the stored labels and label the other faces automatically"),
        ),
        default='STORED')
    iterations: IntProperty(
        name="Iterations", description="Most solver iterations to run",
        default=100, min=1, soft_max=1000)
    tolerance: FloatProperty(
        name="Tolerance",
        description="Stop once every face's normal is within this many degrees of its label's axis "
                    "(0: run every iteration)",
        default=0.5, min=0.0, soft_max=10.0, precision=3)
    variant: EnumProperty(
        name="Solver", description="How the solver steps towards the polycube",
        items=variant_items(), default=DEFAULT_VARIANT.upper())
    rerun_from_result: BoolProperty(
        name="Quick Further Runs",
        description="Robust solver, 100,000 triangles and more: the runs that relabel collapsed faces start "
                    "from the result instead of the input, untangled only around those faces. Several times "
                    "faster on large meshes; a somewhat different polycube",
        default=False)
    coarse_triangles: IntProperty(
        name="Coarse Triangles",
        description="Robust solver: a mesh of at least four times this many triangles whose labels do not "
                    "flatten without help is decimated to about this many, its charts kept, deformed there "
                    "and carried back: minutes become seconds at a million triangles (0: always deform the "
                    "mesh itself)",
        default=DEFAULT_COARSE_TRIANGLES, min=0, soft_max=200000, step=1000)
    keep: EnumProperty(
        name="Keep", description="Which iterations become shape keys",
        items=(
            ('ALL', "All", "A shape key for every iteration"),
            ('EVERY', "Every k-th", "A shape key every k-th iteration, and the last one"),
            ('FINAL', "Final", "Only the last iteration"),
        ),
        default='ALL')
    keep_every: IntProperty(
        name="Every", description="Keep every k-th iteration", default=5, min=1, soft_max=100)
    animate: BoolProperty(
        name="Animate",
        description="Keyframe the shape keys: frame start + k shows iteration k", default=False)
    start_frame: IntProperty(
        name="Start Frame", description="Frame that shows the input mesh", default=1)
    fit_frame_range: BoolProperty(
        name="Fit Frame Range",
        description="Set the scene's start and end frames to the animation's (otherwise they stay as they are)",
        default=False)
    subdivide: BoolProperty(
        name="Subdivide Before",
        description="Deform a subdivided copy, the object '<name> polycube', instead of the mesh itself",
        default=False)
    subdivide_levels: IntProperty(
        name="Levels", description="Subdivision levels: each one splits every face in four",
        default=1, min=1, max=MAX_REFINE_LEVELS, soft_max=min(6, MAX_REFINE_LEVELS))
    subdivide_scheme: EnumProperty(
        name="Scheme", description="How OpenSubdiv places the new vertices",
        items=(
            ('BILINEAR', "Bilinear", "Split faces in place: the shape stays exactly as it is"),
            ('LOOP', "Loop", "Smooth subdivision of triangle meshes"),
            ('CATMARK', "Catmull-Clark", "Smooth subdivision into quads"),
        ),
        default='BILINEAR')

    def draw_settings(self, layout):
        # Values and check boxes get the whole width: the sidebar is narrow.
        layout.use_property_decorate = False
        layout.prop(self, "label_source", text="", icon='FACESEL')
        column = layout.column()
        column.use_property_split = True
        if self.label_source != 'STORED':
            column.prop(self, "detail")
        column.prop(self, "iterations")
        column.prop(self, "tolerance")
        column.prop(self, "variant")
        if self.variant == 'ROBUST':
            column.prop(self, "rerun_from_result")
            column.prop(self, "coarse_triangles")
        column.prop(self, "keep")
        if self.keep == 'EVERY':
            column.prop(self, "keep_every")
        layout.prop(self, "animate")
        if self.animate:
            column = layout.column()
            column.use_property_split = True
            column.prop(self, "start_frame")
            layout.prop(self, "fit_frame_range")
        layout.prop(self, "subdivide")
        if self.subdivide:
            column = layout.column()
            column.use_property_split = True
            column.prop(self, "subdivide_levels")
            column.prop(self, "subdivide_scheme")

    def copy_settings_to(self, target):
        for name in _setting_names(DeformSettings):
            setattr(target, name, getattr(self, name))

    def snapshot(self):
        """The values as a plain RunSettings, safe to read from the solver thread."""
        return RunSettings(*(getattr(self, name) for name in RunSettings._fields))


class RunSettings(namedtuple("RunSettings", _setting_names(DeformSettings))):
    __slots__ = ()

    def keeps(self, iteration):
        """Whether this iteration becomes a shape key (the last one always does)."""
        if self.keep == 'ALL':
            return True
        if self.keep == 'EVERY':
            return iteration % self.keep_every == 0
        return False


class PolycubeSceneSettings(DeformSettings, bpy.types.PropertyGroup):
    pass


def register():
    bpy.types.Scene.polycube = PointerProperty(type=PolycubeSceneSettings)


def unregister():
    del bpy.types.Scene.polycube
