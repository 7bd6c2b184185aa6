"""The polycube iteration of docs/design.md section 2 written the way a user would
with NumPy and SciPy: the reference the benchmark compares the native solver
against, and a second implementation the tests check it with.

Same conventions as the native core: clamped cotangents, a 1e-8 relative
diagonal shift with the matching term on the right, each component's centroid
restored. Triangle meshes only (the benchmark's models are).
"""
import time

import numpy as np
import scipy.sparse
import scipy.sparse.csgraph
import scipy.sparse.linalg

MAX_COTANGENT = 1e3
RELATIVE_SHIFT = 1e-8


def label_axes(labels):
    axes = np.zeros((len(labels), 3))
    axes[np.arange(len(labels)), labels // 2] = np.where(labels % 2 == 0, 1.0, -1.0)
    return axes


def cotangent_weights(x, triangles):
    """(m, 3): cot(angle at corner k) / 2, clamped, for the edge opposite k."""
    weights = np.empty(triangles.shape)
    for k in range(3):
        p = x[triangles[:, k]]
        a, b = x[triangles[:, (k + 1) % 3]] - p, x[triangles[:, (k + 2) % 3]] - p
        sine, cosine = np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b)
        with np.errstate(divide="ignore", invalid="ignore"):
            cot = np.where(sine > 0, cosine / sine, np.sign(cosine) * MAX_COTANGENT)
        weights[:, k] = 0.5 * np.clip(cot, -MAX_COTANGENT, MAX_COTANGENT)
    return weights


def laplacian(n, triangles, weights):
    rows, cols, values = [], [], []
    for k in range(3):
        v, w, c = triangles[:, (k + 1) % 3], triangles[:, (k + 2) % 3], weights[:, k]
        rows += [v, w, v, w]
        cols += [w, v, v, w]
        values += [-c, -c, c, c]
    return scipy.sparse.csc_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))),
                                   shape=(n, n))


def rotations(normals, axes):
    """Rodrigues per triangle, with the half-turn composition beyond 90 degrees."""
    def within_90(n, t):
        v, c = np.cross(n, t), np.einsum("ij,ij->i", n, t)
        k = np.zeros((len(n), 3, 3))
        k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -v[:, 2], v[:, 1], -v[:, 0]
        k[:, 1, 0], k[:, 2, 0], k[:, 2, 1] = v[:, 2], -v[:, 1], v[:, 0]
        return np.eye(3) + k + k @ k / (1.0 + c)[:, None, None]

    with np.errstate(divide="ignore", invalid="ignore"):  # opposite pairs are redone below
        r = within_90(normals, axes)
    opposite = np.einsum("ij,ij->i", normals, axes) < 0
    if opposite.any():
        n, t = normals[opposite], axes[opposite]
        a = np.cross(n, t)
        length = np.linalg.norm(a, axis=1)
        fallback = np.cross(n, np.where(np.abs(n[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]]))
        a = np.where(length[:, None] > 1e-12, a, fallback)
        a /= np.linalg.norm(a, axis=1)[:, None]
        half_turn = 2 * a[:, :, None] * a[:, None, :] - np.eye(3)
        r[opposite] = within_90(-n, t) @ half_turn
    return r


def rhs(x, triangles, weights, axes):
    p = [x[triangles[:, k]] for k in range(3)]
    normals = np.cross(p[1] - p[0], p[2] - p[0])
    length = np.linalg.norm(normals, axis=1)
    r = np.tile(np.eye(3), (len(triangles), 1, 1))
    ok = length > 0
    r[ok] = rotations(normals[ok] / length[ok, None], axes[ok])
    b = np.zeros_like(x)
    for k in range(3):
        i, j = (k + 1) % 3, (k + 2) % 3
        term = weights[:, k, None] * np.einsum("fij,fj->fi", r, p[i] - p[j])
        for axis in range(3):
            b[:, axis] += np.bincount(triangles[:, i], term[:, axis], len(x))
            b[:, axis] -= np.bincount(triangles[:, j], term[:, axis], len(x))
    return b


def deform(vertices, triangles, labels, iterations, variant="fixed", seconds=None):
    """Positions after `iterations` iterations (no early stop). `seconds`, a
    dict, receives the time of the set-up (`setup`, including the first
    factorisation) and of each iteration (`iterations`, a list)."""
    start = time.perf_counter()
    x = np.array(vertices, dtype=float)
    triangles = np.asarray(triangles)
    n = len(x)
    axes = label_axes(np.asarray(labels))
    adjacency = scipy.sparse.coo_matrix((np.ones(triangles.size), (np.repeat(triangles[:, 0], 3), triangles.ravel())),
                                        shape=(n, n))
    _, component = scipy.sparse.csgraph.connected_components(adjacency, directed=False)
    used = np.zeros(n, bool)
    used[triangles.ravel()] = True
    count = np.bincount(component[used], minlength=component.max() + 1)[:, None]

    def centroids(y):
        return np.stack([np.bincount(component[used], y[used, a], len(count)) for a in range(3)], 1) / np.maximum(count, 1)

    target = centroids(x)
    solve = weights = shift = None
    for iteration in range(iterations):
        if iteration == 1 and seconds is not None:
            seconds["setup"] = time.perf_counter() - start - seconds["iterations"][0]
        lap = time.perf_counter()
        if solve is None or variant == "current":
            weights = cotangent_weights(x if variant == "current" else vertices, triangles)
            matrix = laplacian(n, triangles, weights)
            shift = RELATIVE_SHIFT * np.abs(matrix.diagonal()).mean()
            solve = scipy.sparse.linalg.factorized((matrix + shift * scipy.sparse.identity(n)).tocsc())
        b = rhs(x, triangles, weights, axes) + shift * x
        y = np.stack([solve(b[:, a]) for a in range(3)], 1)
        y[used] -= (centroids(y) - target)[component[used]]
        y[~used] = vertices[~used]
        x = y
        if seconds is not None:
            seconds.setdefault("iterations", []).append(time.perf_counter() - lap)
    return x
