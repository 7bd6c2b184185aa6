# SPDX-License-Identifier: GPL-3.0-or-later
"""The solver on a worker thread, talking to Blender's main thread through a queue.

The native solver releases the GIL while it computes, so Blender keeps drawing and
handling events. Nothing here touches bpy: only the main thread may.
"""

import queue
import threading
from time import perf_counter

from . import polycube_native

# Kept iterations in flight at once. The solver can be far faster than writing
# shape keys; past this many it waits, so memory stays bounded and Esc acts soon.
_IN_FLIGHT = 4


class SolverThread(threading.Thread):
    """Runs polycube_native.deform; messages, in order, from `messages()`:
    ("iteration", k, positions or None, figures, moved) ... then ("done", result,
    seconds spent solving, the callback's waits left out) or ("error", exception)."""

    def __init__(self, args, kwargs, keeps, watch):
        """`keeps(iteration)`: whether the iteration becomes a shape key; `watch`: a
        ProgressWatch, owned by this thread until it ends."""
        super().__init__(name="polycube solver", daemon=True)
        self._queue = queue.Queue()
        self._slots = threading.Semaphore(_IN_FLIGHT)
        self._args, self._kwargs, self._keeps, self._watch = args, kwargs, keeps, watch
        self._stop_requested = threading.Event()

    def request_stop(self):
        """Stop after the current iteration; the iterations done are kept."""
        self._stop_requested.set()

    def run(self):
        outside = [0.0]  # seconds spent in the callback: not solving

        def on_iteration(iteration, positions, figures):
            entered = perf_counter()
            moved = self._watch.update(iteration, positions)
            # Only kept iterations that moved carry positions, and only a few at a time.
            kept = positions if moved and self._keeps(iteration) else None
            if kept is not None:
                self._slots.acquire()  # waits while Blender writes earlier keys
            self._queue.put(("iteration", iteration, kept, figures, moved))
            outside[0] += perf_counter() - entered
            return not self._stop_requested.is_set() and not self._watch.stalled

        start = perf_counter()
        try:
            result = polycube_native.deform(*self._args, callback=on_iteration,
                                            stop=self._stop_requested.is_set, **self._kwargs)
        except Exception as error:  # handed to the main thread, which reports it
            self._queue.put(("error", error))
        else:
            self._queue.put(("done", result, perf_counter() - start - outside[0]))

    def messages(self, seconds):
        """The messages waiting now, for at most this long, without blocking."""
        end = perf_counter() + seconds
        while perf_counter() < end:
            try:
                message = self._queue.get_nowait()
            except queue.Empty:
                return
            if message[0] == "iteration" and message[2] is not None:
                self._slots.release()
            yield message
