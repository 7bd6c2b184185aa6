# SPDX-License-Identifier: GPL-3.0-or-later
"""One native call on a worker thread, so Blender keeps drawing and handling
events while it runs (the native module releases the GIL). Nothing here
touches bpy: only the main thread may, once `done`.

The native calls cannot be interrupted: a call the user gave up on (Esc) runs
to its end in the background and its result is dropped."""

import threading
from time import perf_counter


class BackgroundCall(threading.Thread):
    def __init__(self, function, *args, **kwargs):
        super().__init__(name="polycube worker", daemon=True)
        self._call = (function, args, kwargs)
        self.result = None
        self.error = None
        self.started_at = perf_counter()
        self.start()

    def run(self):
        function, args, kwargs = self._call
        try:
            self.result = function(*args, **kwargs)
        except Exception as error:  # handed to the main thread, which reports it
            self.error = error

    @property
    def done(self):
        return not self.is_alive()

    @property
    def seconds(self):
        return perf_counter() - self.started_at
