# SPDX-License-Identifier: GPL-3.0-or-later
"""Reading Object File Format (.off) meshes, which Blender has no importer for.

Knows nothing of Blender: returns the solver's arrays. Accepts the OFF header
variants with colours or normals per vertex (COFF, NOFF, CNOFF, ...; only the first
three numbers of a vertex are used) and ignores comments and per-face colours.
"""

import numpy as np


def read_off(path):
    """(vertices (n, 3) float64, face_indices int32, face_sizes int32); ValueError if malformed."""
    with open(path, "r", encoding="utf-8", errors="replace") as file:
        lines = [line.split("#", 1)[0].split() for line in file]
    lines = [tokens for tokens in lines if tokens]
    if not lines or not lines[0][0].upper().endswith("OFF"):
        raise ValueError(f"{path} is not an OFF file: it does not start with OFF")
    header = lines[0][1:] or lines[1]
    body = lines[1:] if lines[0][1:] else lines[2:]
    try:
        vertex_count, face_count = int(header[0]), int(header[1])
        vertex_rows, face_rows = body[:vertex_count], body[vertex_count:vertex_count + face_count]
        if len(vertex_rows) < vertex_count or len(face_rows) < face_count:
            raise ValueError
        vertices = np.array([row[:3] for row in vertex_rows], dtype=np.float64).reshape(-1, 3)
        face_sizes = np.array([row[0] for row in face_rows], dtype=np.int32)
        face_indices = np.array(
            [index for row, size in zip(face_rows, face_sizes) for index in row[1:1 + size]],
            dtype=np.int32)
    except (ValueError, IndexError):
        raise ValueError(f"{path} is not a valid OFF file: its counts or numbers do not add up") from None
    if len(face_indices) != face_sizes.sum() or (
            len(face_indices) and (face_indices.min() < 0 or face_indices.max() >= vertex_count)):
        raise ValueError(f"{path} is not a valid OFF file: a face refers to a missing vertex")
    return vertices, face_indices, face_sizes
