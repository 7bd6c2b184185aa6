"""The native solver against the NumPy/SciPy reference (tests/benchmark):
two independent implementations of docs/design.md section 2 must agree."""
import pathlib
import sys

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "benchmark"))
reference = pytest.importorskip("reference_scipy", reason="needs python3-scipy")


@pytest.mark.parametrize("variant", ["fixed", "current"])
def test_native_and_scipy_agree_after_five_iterations(native, real_mesh, variant):
    vertices, indices, sizes = real_mesh("fandisk")
    labels = native.nearest_labels(vertices, indices, sizes)
    ours = native.deform(vertices, indices, sizes, labels, iterations=5, tolerance=0, variant=variant)["positions"]
    theirs = reference.deform(vertices, indices.reshape(-1, 3), labels, 5, variant)
    diagonal = np.linalg.norm(np.ptp(vertices, axis=0))
    assert np.abs(ours - theirs).max() < 1e-8 * diagonal


def test_rotations_match_on_opposite_and_random_normals():
    rng = np.random.default_rng(3)
    n = rng.normal(size=(500, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    t = reference.label_axes(rng.integers(0, 6, 500))
    n[:6] = -reference.label_axes(np.arange(6))
    t[:6] = reference.label_axes(np.arange(6))
    r = reference.rotations(n, t)
    assert np.abs(np.einsum("fij,fj->fi", r, n) - t).max() < 1e-12
