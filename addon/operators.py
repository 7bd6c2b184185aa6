# SPDX-License-Identifier: GPL-3.0-or-later
"""Deform to Polycube: the operator.

`execute` runs each object to the end (background mode, scripts, the redo panel);
`invoke` in the UI runs the slow parts on worker threads: first the automatic labels
and the refinement (Esc then cancels with nothing changed), then the solver, whose
iterations a timer writes (Esc then stops early, keeping what is written). Blender
stays responsive and the status bar says what runs from the start.
"""

from time import perf_counter

import bpy

from . import polycube_native, preferences
from .background_call import BackgroundCall
from .object_run import ObjectRun
from .redo_estimate import RedoEstimate
from .report import advice, failure, outcome, work_seconds
from .settings import DeformSettings
from .solver_thread import SolverThread
from .subdivide import source_object

# Events that reach the rest of Blender while the solver (or the labeller) runs:
# looking around only, so nothing can edit, undo or delete the object being written to.
PASS_THROUGH = {
    'MIDDLEMOUSE', 'WHEELUPMOUSE', 'WHEELDOWNMOUSE', 'WHEELINMOUSE', 'WHEELOUTMOUSE',
    'MOUSEMOVE', 'INBETWEEN_MOUSEMOVE', 'TRACKPADPAN', 'TRACKPADZOOM', 'MOUSEROTATE',
    'MOUSESMARTZOOM', 'NDOF_MOTION', 'WINDOW_DEACTIVATE', 'TIMER', 'TIMERREPORT',
}


class OBJECT_OT_polycube_deform(RedoEstimate, DeformSettings, bpy.types.Operator):
    """Deform the selected mesh objects into their polycube, a shape key per iteration"""
    bl_idname = "object.polycube_deform"
    bl_label = "Deform to Polycube"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        if context.mode != 'OBJECT':
            cls.poll_message_set("Switch to Object Mode first")
            return False
        if not context.selected_objects:
            cls.poll_message_set("Select one or more mesh objects")
            return False
        return True

    def draw(self, context):
        self.draw_settings(self.layout)
        self.draw_estimate(self.layout)

    def execute(self, context):
        self._problems, self._reports = [], []
        for run in self._prepare(context):
            try:
                run.adopt(run.compute())
            except (ValueError, RuntimeError) as error:
                self._fail(run, error)
                continue
            args, kwargs = run.solver_call()
            outside = [0.0]  # seconds in the callback (the watch, writing keys): not solving

            def on_iteration(*message, run=run, outside=outside):
                entered = perf_counter()
                go_on = run.add_iteration(*message)
                outside[0] += perf_counter() - entered
                return go_on

            start = perf_counter()
            try:
                result = polycube_native.deform(*args, callback=on_iteration, **kwargs)
                self._reports.append(run.finish(result, perf_counter() - start - outside[0]))
            except (ValueError, RuntimeError) as error:
                self._fail(run, error)
        return self._conclude(context)

    def invoke(self, context, event):
        if bpy.app.background:
            return self.execute(context)
        self._problems, self._reports = [], []
        self._pending = self._prepare(context)
        if not self._pending:
            return self._conclude(context)
        self._cancelled = False
        self._iterations_before = 0
        self._call = self._thread = None
        wm = context.window_manager
        wm.progress_begin(0, len(self._pending) * self.iterations)
        self._timer = wm.event_timer_add(0.05, window=context.window)
        wm.modal_handler_add(self)
        self._start_next(context)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if event.type == 'ESC' and event.value == 'PRESS':
            self._cancelled = True
            if self._call is not None:
                # Labels or refinement under way: nothing is written yet, and nothing will be.
                self._call = None
                self._problems.append(f"Cancelled before '{self._run.object_name}' was deformed.")
                self._next_object(context)
                return self._end(context)
            self._thread.request_stop()
            context.workspace.status_text_set("Polycube: stopping after this iteration...")
            return {'RUNNING_MODAL'}
        if event.type == 'TIMER' and self._pump(context):
            return self._end(context)
        return {'PASS_THROUGH'} if event.type in PASS_THROUGH else {'RUNNING_MODAL'}

    def cancel(self, context):
        # Blender is closing the window: let the threads go, keep what is written.
        if self._thread is not None:
            self._thread.request_stop()
        self._cleanup(context)

    def _prepare(self, context):
        """An ObjectRun for each selected mesh that can be deformed; the rest go to _problems."""
        settings = self.snapshot()
        runs, meshes, objects = [], set(), []
        for obj in sorted(context.selected_objects, key=lambda o: o.name):
            if obj.type == 'MESH' and settings.subdivide:
                obj = source_object(obj)  # a subdivided copy is made again from its source
            if obj not in objects:
                objects.append(obj)
        for obj in objects:
            if obj.type != 'MESH':
                self._problems.append(f"Skipped '{obj.name}': it is {_a(obj.type.lower())}, not a mesh.")
                continue
            if obj.data.name in meshes:
                self._problems.append(
                    f"Skipped '{obj.name}': it shares its mesh with an object deformed already.")
                continue
            try:
                runs.append(ObjectRun(obj, settings))
                meshes.add(obj.data.name)
            except ValueError as error:
                self._problems.append(failure(obj.name, "deformed", error))
        return runs

    def _start_next(self, context):
        """Labels and refinement for the next object, on a worker thread."""
        self._run = self._pending.pop(0)
        self._run_error = None
        self._thread = None
        self._call = BackgroundCall(self._run.compute)
        self._show_preparation(context)

    def _start_solver(self, context):
        self._run.adopt(self._call.result)
        self._call = None
        self._run.live_preview = preferences.live_preview(context)
        args, kwargs = self._run.solver_call()
        self._thread = SolverThread(args, kwargs, self._run.settings.keeps, self._run.watch)
        self._thread.start()
        context.workspace.status_text_set(
            f"Polycube: '{self._run.object_name}' setting up the solver (Esc to stop)")

    def _pump(self, context):
        """Move the current object's run on; True once every object is done."""
        if self._call is not None:
            if not self._call.done:
                self._show_preparation(context)
                return False
            try:
                if self._call.error is not None:
                    raise self._call.error
                self._start_solver(context)
            except (ValueError, RuntimeError) as error:
                self._call = None
                self._fail(self._run, error)
                return self._next_object(context)
            return False
        # A time budget per timer event, so that writing keys never freezes the UI.
        for message in self._thread.messages(seconds=0.1):
            kind = message[0]
            if kind == "iteration":
                if self._run_error is None:
                    _, iteration, positions, figures, moved = message
                    try:
                        self._run.add_iteration(iteration, positions, figures, moved)
                    except (ValueError, RuntimeError) as error:
                        # Keep draining: the thread may wait for the queue to empty.
                        self._run_error = error
                        self._thread.request_stop()
                    else:
                        self._show_progress(context, iteration, figures)
                continue
            if kind == "error":
                self._run_error = message[1]
            elif self._run_error is None:
                try:
                    self._reports.append(self._run.finish(*message[1:]))
                except (ValueError, RuntimeError) as error:
                    self._run_error = error
            if self._run_error is not None:
                self._fail(self._run, self._run_error)
            return self._next_object(context)
        return False

    def _next_object(self, context):
        """Start the next object's run; True when there is none left to run."""
        self._iterations_before += self.iterations
        if self._cancelled:
            for run in self._pending:  # nothing is made for a run before it starts
                self._problems.append(f"Cancelled before '{run.object_name}' was deformed.")
            self._pending = []
        if not self._pending:
            return True
        self._start_next(context)
        return False

    def _show_preparation(self, context):
        settings = self._run.settings
        work = [what for what, asked in (("labelling", settings.label_source != 'STORED'),
                                         ("subdividing", settings.subdivide)) if asked]
        context.workspace.status_text_set(
            f"Polycube: '{self._run.object_name}' {' and '.join(work) or 'reading labels'}, "
            f"{self._call.seconds:.1f} s (Esc to cancel)")

    def _show_progress(self, context, iteration, figures):
        context.window_manager.progress_update(self._iterations_before + iteration)
        for area in context.screen.areas:
            if area.type == 'VIEW_3D':
                area.tag_redraw()
        if self._cancelled:
            return  # the status bar says it is stopping
        context.workspace.status_text_set(
            f"Polycube: '{self._run.object_name}' iteration {iteration}/{self.iterations}, "
            f"max deviation {figures['normal_deviation_max_deg']:.3f}°, "
            f"{figures['flipped_faces']} flipped faces (Esc to stop)")

    def _end(self, context):
        self._cleanup(context)
        return self._conclude(context)

    def _cleanup(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)

    def _fail(self, run, error):
        run.discard()
        self._problems.append(failure(run.object_name, "deformed", error))

    def _conclude(self, context):
        """Report what happened; FINISHED when at least one object was deformed."""
        self.last_seconds = sum(work_seconds(report) for report in self._reports)
        if not self._reports:
            # Esc before anything was written is the user's choice, not an error.
            level = {'WARNING'} if getattr(self, "_cancelled", False) else {'ERROR'}
            for problem in self._problems:
                self.report(level, problem)
            return {'CANCELLED'}
        for problem in self._problems:
            self.report({'WARNING'}, problem)
        _select_copies(context, self._reports)
        ends = [report["animation_frames"][1] for report in self._reports
                if "animation_frames" in report]
        if ends:
            scene = context.scene
            if self.fit_frame_range:
                scene.frame_start, scene.frame_end = self.start_frame, max(ends)
            scene.frame_set(max(ends))  # the polycube shows
        for report in self._reports:
            self.report({'INFO'}, _summary(report))
        return {'FINISHED'}


def _select_copies(context, reports):
    """Subdivided copies become the selection, as Blender's own Duplicate and Convert do."""
    copies = [(bpy.data.objects.get(report["object"]), bpy.data.objects.get(report["subdivided_from"]))
              for report in reports if "subdivided_from" in report]
    for copy, source in copies:
        if source is not None:
            source.select_set(False)
        if copy is not None:
            copy.select_set(True)
            context.view_layer.objects.active = copy


def _a(noun):
    """The noun with its indefinite article: 'an empty', 'a curve'."""
    return ("an " if noun[:1] in "aeiou" else "a ") + noun


def _summary(report):
    summary = (f"'{report['object']}': {outcome(report)} after {report['iterations']} iterations, "
               f"max normal deviation {report['normal_deviation_max_deg']:.3f}°, "
               f"{report['flipped_faces']} flipped faces, "
               f"{len(report['kept_iterations'])} shape keys.")
    hint = advice(report)
    return f"{summary} Not a polycube yet: {'; '.join(line[0].lower() + line[1:] for line in hint)}." \
        if hint else summary
