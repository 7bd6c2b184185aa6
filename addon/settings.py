# SPDX-License-Identifier: GPL-3.0-or-later
"""The deformation settings, declared once for the operator and the panel.

The operator inherits them (redo panel); the scene keeps a copy
(`scene.polycube`) so the sidebar remembers what the user chose between runs.
"""

from collections import namedtuple

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty


class DeformSettings:
    iterations: IntProperty(
        name="Iterations", description="Most solver iterations to run",
        default=100, min=1, soft_max=1000)
    tolerance: FloatProperty(
        name="Tolerance",
        description="Stop once every face's normal is within this many degrees of its label's axis",
        default=0.5, min=1e-4, soft_max=10.0, precision=3)
    variant: EnumProperty(
        name="Solver", description="Which Laplacian the solver uses",
        items=(
            ('FIXED', "Fixed", "Cotangent Laplacian of the input mesh, factorised once: fast"),
            ('CURRENT', "Current",
             "Laplacian of the current mesh, refactorised every iteration (as in the paper)"),
        ),
        default='FIXED')
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

    def draw_settings(self, layout):
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(self, "iterations")
        layout.prop(self, "tolerance")
        layout.prop(self, "variant")
        layout.prop(self, "keep")
        if self.keep == 'EVERY':
            layout.prop(self, "keep_every")
        layout.prop(self, "animate")
        if self.animate:
            layout.prop(self, "start_frame")

    def copy_settings_to(self, target):
        for name in DeformSettings.__annotations__:
            setattr(target, name, getattr(self, name))

    def snapshot(self):
        """The values as a plain RunSettings, safe to read from the solver thread."""
        return RunSettings(*(getattr(self, name) for name in RunSettings._fields))


class RunSettings(namedtuple("RunSettings", DeformSettings.__annotations__)):
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
