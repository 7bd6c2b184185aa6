"""Shared fixtures: the built module and program, generated meshes, real models.

The module is imported from the build directory (POLYCUBE_BUILD, default
build/), so these tests run against exactly what `make build` produced.
"""
import os
import pathlib
import sys

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("POLYCUBE_BUILD", ROOT / "build")).resolve()
MESHES = BUILD / "data" / "meshes"
SHARED_DATA = ROOT.parent / "shared" / "data"
sys.path.insert(0, str(BUILD))

import polycube_native  # noqa: E402


@pytest.fixture(scope="session")
def native():
    return polycube_native


@pytest.fixture(scope="session")
def program():
    path = BUILD / "polycube"
    if not path.exists():
        pytest.fail(f"{path} is missing: run `make build`")
    return str(path)


def uv_sphere(segments=32, rings=16, radii=(1.0, 1.0, 1.0)):
    """Quads with triangle fans at the poles, as flat arrays for the module."""
    points = [(0.0, 0.0, 1.0)]
    for i in range(1, rings):
        theta = np.pi * i / rings
        for j in range(segments):
            phi = 2 * np.pi * j / segments
            points.append((np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)))
    points.append((0.0, 0.0, -1.0))
    faces = [[0, 1 + j, 1 + (j + 1) % segments] for j in range(segments)]
    for i in range(rings - 2):
        for j in range(segments):
            a, b = 1 + i * segments + j, 1 + i * segments + (j + 1) % segments
            faces.append([a, a + segments, b + segments, b])
    last, base = len(points) - 1, 1 + (rings - 2) * segments
    faces += [[base + j, last, base + (j + 1) % segments] for j in range(segments)]
    vertices = np.array(points) * np.array(radii)
    return vertices, np.concatenate(faces), np.array([len(f) for f in faces])


def read_off(path):
    """A minimal OFF reader for the tests (the product's reader is native)."""
    words = []
    for line in pathlib.Path(path).read_text().splitlines():
        words += line.split("#")[0].split()
    assert words[0].endswith("OFF")
    nv, nf = int(words[1]), int(words[2])
    at = 4
    vertices = np.array(words[at:at + 3 * nv], dtype=float).reshape(nv, 3)
    at += 3 * nv
    indices, sizes = [], []
    for _ in range(nf):
        k = int(words[at])
        indices += words[at + 1:at + 1 + k]
        sizes.append(k)
        at += 1 + k
    return vertices, np.array(indices, dtype=np.int32), np.array(sizes, dtype=np.int32)


@pytest.fixture
def sphere():
    return uv_sphere()


@pytest.fixture(scope="session")
def real_mesh():
    def load(name):
        path = MESHES / f"{name}.off"
        if not path.exists():
            pytest.skip(f"{path} is missing: run `make data` (Debian libcgal-demo)")
        return read_off(path)
    return load
