# SPDX-License-Identifier: GPL-3.0-or-later
"""One object's deformation: inputs read from Blender, iterations written back.

The same object serves the synchronous run (background mode, redo panel) and the
modal one (in threads). Its steps, in order: the constructor reads the object (main
thread); `compute` makes the automatic labels and the refinement the settings ask
for (native work only: any thread); `adopt` takes them in and makes the subdivided
copy (main thread); then whoever drives the solver hands each iteration to
`add_iteration` on the main thread and the result to `finish`.
"""

from time import perf_counter

import bpy

from . import animation, shape_keys
from .label_source import is_automatic, labels_for_run, stored_labels
from .labels import label_counts
from .mesh_arrays import read_mesh_arrays
from .polycube_native import LABEL_NAMES
from .progress_watch import STILL_ITERATIONS, ProgressWatch
from .report import store_labels_used, store_report
from .settings import label_options
from .subdivide import check_copy_name, refine_mesh, remove_copy, subdivided_copy


class ObjectRun:
    def __init__(self, obj, settings):
        """Read the object's mesh and stored labels; ValueError (one sentence), with
        nothing written, if it cannot run."""
        start = perf_counter()
        self.settings = settings
        self.mesh = read_mesh_arrays(obj.data)
        self._stored = stored_labels(obj, settings.label_source)
        self.object_name = obj.name
        self.source_name = None  # the object a subdivided copy was made from
        if settings.subdivide:
            check_copy_name(obj)
            self.source_name = obj.name
        self.labels = None  # set by adopt
        self.labels_automatic = False
        self.seconds_read = perf_counter() - start
        self.seconds_write = 0.0
        self.kept = []  # iterations written as shape keys, in order
        self.watch = None
        self.live_preview = False
        self._started = False

    def compute(self):
        """The labels (automatic where the settings ask) and the refined mesh (None without
        Subdivide Before), for `adopt`. Touches no Blender data: may run on a worker thread;
        ValueError if the labeller or the refinement refuses the mesh."""
        start = perf_counter()
        settings = self.settings
        labels = labels_for_run(self._stored, self.mesh, settings.label_source, label_options(settings))
        refined = refine_mesh(self.mesh, labels, settings.subdivide_levels, settings.subdivide_scheme) \
            if settings.subdivide else None
        return labels, refined, perf_counter() - start

    def adopt(self, computed):
        """Take compute's result in (main thread): make the subdivided copy, ready the watch."""
        labels, refined, seconds = computed
        start = perf_counter()
        obj = self._object()
        self.labels_automatic = is_automatic(obj, labels)
        if refined is not None:
            obj, self.mesh, labels = subdivided_copy(
                obj, refined, labels, self.settings.subdivide_levels, self.settings.subdivide_scheme)
            self.object_name = obj.name
        self.labels = labels
        self.seconds_read += seconds + perf_counter() - start
        # Tolerance 0 asks for every iteration: still ones get no key, but the run goes on.
        still = STILL_ITERATIONS if self.settings.tolerance > 0 else 0
        self.watch = ProgressWatch(self.mesh.vertices, still_iterations=still)

    def solver_call(self):
        """Positional and keyword arguments for polycube_native.deform."""
        args = (self.mesh.vertices, self.mesh.face_indices, self.mesh.face_sizes, self.labels.values)
        kwargs = dict(iterations=self.settings.iterations, tolerance=self.settings.tolerance,
                      variant=self.settings.variant.lower(), rerun_from_result=self.settings.rerun_from_result,
                      coarse_triangles=self.settings.coarse_triangles)
        return args, kwargs

    def add_iteration(self, iteration, positions, figures, moved=None):
        """positions may be None for iterations the settings do not keep; `moved` is
        what self.watch said of them (asked here when None). An iteration that did
        not move the mesh gets no shape key. Returns whether to go on."""
        if moved is None:
            moved = self.watch.update(iteration, positions)
        if moved and positions is not None and self.settings.keeps(iteration):
            block = self._write(iteration, positions)
            if self.live_preview:
                # Only the previous key needs switching off: the others already are.
                if len(self.kept) > 1:
                    blocks = block.id_data.key_blocks
                    blocks[shape_keys.key_name(self.kept[-2], self.settings.iterations)].value = 0.0
                block.value = 1.0
        return not self.watch.stalled

    def finish(self, result, seconds_solve):
        """Write the last iteration if not yet kept, animate, store the report; returns it."""
        report = dict(result["report"])
        # The final positions are those of the last iteration that moved the mesh.
        last = self.watch.last_moved
        if last > 0 and (not self.kept or self.kept[-1] != last):
            self._write(last, result["positions"])
        if self.watch.stalled:
            report.update(stalled_at=self.watch.stalled_at, moved_until=self.watch.last_moved)
        obj = self._object()
        if not self._started:
            # Nothing to write (already a polycube): earlier Polycube keys are stale.
            self._start(obj)
        start = perf_counter()
        keys = shape_keys.polycube_keys(obj)
        if keys:
            obj.active_shape_key_index = obj.data.shape_keys.key_blocks.find(keys[-1][1].name)
            if self.settings.animate:
                report["animation_frames"] = [self.settings.start_frame,
                                              animation.animate(obj, self.settings.start_frame)]
            else:
                shape_keys.show_only(obj, keys[-1][1])
        self.seconds_write += perf_counter() - start

        counts, unlabelled = label_counts(self.labels.values)
        if self.source_name is not None:
            report["subdivided_from"] = self.source_name
        report.update(
            object=self.object_name,
            label_source=self.labels.source,
            label_counts=dict(zip(LABEL_NAMES, counts)),
            labelled_faces=len(self.labels.values) - unlabelled,
            labels_automatic=self.labels_automatic,
            kept_iterations=list(self.kept),
        )
        report["seconds"] = dict(report["seconds"], read=self.seconds_read,
                                 deform_call=seconds_solve, write=self.seconds_write)
        store_report(obj, report)
        store_labels_used(obj, result["labels"])
        return report

    def discard(self):
        """Take back what this run wrote (the run failed half-way): its keys or its copy."""
        obj = bpy.data.objects.get(self.object_name)
        if obj is not None and self.source_name not in (None, self.object_name):
            remove_copy(obj)
        elif obj is not None and self._started:
            animation.clear_animation(obj)
            shape_keys.remove_polycube_keys(obj)

    def _object(self):
        # Look the object up each time: the run spans many timer events in the UI.
        obj = bpy.data.objects.get(self.object_name)
        if obj is None or obj.type != 'MESH' or len(obj.data.vertices) != len(self.mesh.vertices):
            raise RuntimeError(f"'{self.object_name}' was deleted or changed during the run")
        return obj

    def _start(self, obj):
        animation.clear_animation(obj)
        shape_keys.remove_polycube_keys(obj)
        self._started = True

    def _write(self, iteration, positions):
        start = perf_counter()
        obj = self._object()
        if not self._started:
            self._start(obj)
        block = shape_keys.add_key(
            obj, shape_keys.key_name(iteration, self.settings.iterations), positions)
        self.kept.append(iteration)
        self.seconds_write += perf_counter() - start
        return block
