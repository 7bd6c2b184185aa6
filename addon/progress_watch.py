# SPDX-License-Identifier: GPL-3.0-or-later
"""Noticing a run that stands still, from the positions each iteration hands over.

Where the labels ask for what the solver refuses to do (every flattening
attempt refused, say), the iterations can go on without moving the mesh:
shape keys for them would all be the same. An iteration "moves" when some
vertex is more than STILL_FRACTION of the bounding box diagonal away from
where the last moving iteration left it; after STILL_ITERATIONS iterations
in a row that do not, the run has stalled and is stopped.
"""

import numpy as np

STILL_FRACTION = 1e-6  # about what a float32 shape key can tell apart
STILL_ITERATIONS = 8


class ProgressWatch:
    """Fed every iteration's positions in order; not tied to Blender, so the
    solver thread may own it. still_iterations 0 (or False): never stalls."""

    def __init__(self, vertices, still_iterations=STILL_ITERATIONS, fraction=STILL_FRACTION):
        vertices = np.asarray(vertices, dtype=np.float64)
        diagonal = float(np.linalg.norm(np.ptp(vertices, axis=0))) if len(vertices) else 0.0
        self._squared_step = (fraction * diagonal) ** 2
        self._anchor = vertices.copy()
        self._still = 0
        self._still_iterations = still_iterations
        self.last_moved = 0      # the last iteration that moved (0: none did)
        self.stalled_at = None   # the iteration at which the run counted as stalled

    def update(self, iteration, positions):
        """Whether this iteration moved the mesh; marks the run stalled when it has not
        moved for long enough."""
        squared = np.einsum("ij,ij->i", positions - self._anchor, positions - self._anchor)
        if len(squared) and squared.max() > self._squared_step:
            self._anchor = np.array(positions, dtype=np.float64)
            self._still = 0
            self.last_moved = iteration
            return True
        self._still += 1
        if self._still_iterations and self._still >= self._still_iterations and self.stalled_at is None:
            self.stalled_at = iteration
        return False

    @property
    def stalled(self):
        return self.stalled_at is not None
