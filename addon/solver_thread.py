# SPDX-License-Identifier: GPL-3.0-or-later
"""The solver on a worker thread, talking to Blender's main thread through a queue.

The native solver releases the GIL while it computes, so Blender keeps drawing and
handling events. Nothing here touches bpy: only the main thread may.
"""

import queue
import threading
from time import perf_counter

from . import polycube_native


class SolverThread(threading.Thread):
    """Runs polycube_native.deform; messages on `messages`:
    ("iteration", k, positions or None, figures), then ("done", result, seconds)
    or ("error", exception)."""

    def __init__(self, args, kwargs, keeps):
        super().__init__(name="polycube solver", daemon=True)
        self.messages = queue.Queue()
        self._args, self._kwargs, self._keeps = args, kwargs, keeps
        self._stop_requested = threading.Event()

    def request_stop(self):
        """Stop after the current iteration; the iterations done are kept."""
        self._stop_requested.set()

    def run(self):
        def on_iteration(iteration, positions, figures):
            # Only kept iterations carry positions: the queue may hold many at once.
            kept = positions if self._keeps(iteration) else None
            self.messages.put(("iteration", iteration, kept, figures))
            return not self._stop_requested.is_set()

        start = perf_counter()
        try:
            result = polycube_native.deform(*self._args, callback=on_iteration, **self._kwargs)
        except Exception as error:  # handed to the main thread, which reports it
            self.messages.put(("error", error))
        else:
            self.messages.put(("done", result, perf_counter() - start))

    def drain(self):
        """The messages waiting now, without blocking."""
        while True:
            try:
                yield self.messages.get_nowait()
            except queue.Empty:
                return
