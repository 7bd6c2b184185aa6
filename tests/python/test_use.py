"""Uses of the polycube from Python and the command line: the UV map (`uv`,
`polycube_uv`) and the quad remesh (`remesh`, `quad_remesh`), their figures
and their refusals."""
import json
import subprocess

import numpy as np
import pytest

from conftest import MESHES


def run(program, *args):
    return subprocess.run([program, *map(str, args)], capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def fandisk(program, tmp_path_factory):
    """fandisk and its exact polycube from the program, as files."""
    from conftest import MESHES
    source = MESHES / "fandisk.off"
    if not source.exists():
        pytest.skip(f"{source} is missing: run `make data`")
    folder = tmp_path_factory.mktemp("fandisk")
    polycube, report = folder / "fandisk-polycube.obj", folder / "report.json"
    result = run(program, "deform", source, "--labels", "auto", "--output", polycube, "--report", report)
    assert result.returncode == 0, result.stderr
    assert json.loads(report.read_text())["converged"]
    return source, polycube, folder


def test_uv_command_writes_one_vt_per_corner_and_islands_apart(program, native, fandisk):
    source, polycube, folder = fandisk
    out = folder / "fandisk-uv.obj"
    result = run(program, "uv", source, polycube, "--output", out)
    assert result.returncode == 0, result.stderr
    figures = json.loads(result.stdout)
    lines = out.read_text().splitlines()
    vt = np.array([[float(x) for x in line.split()[1:]] for line in lines if line.startswith("vt ")])
    faces = [line.split()[1:] for line in lines if line.startswith("f ")]
    vertices, indices, sizes = native.read_mesh(str(source))
    assert len(vt) == len(indices) and len(faces) == len(sizes)
    assert all("/" in corner for corner in faces[0])
    assert vt.min() >= 0.0 and vt.max() <= 1.0
    # The same figures from Python, from the written UVs.
    again = native.uv_figures(vertices, indices, sizes, vt)
    assert again["islands"] == figures["islands"] and again["flipped"] == 0
    assert again["angle_distortion"] == pytest.approx(figures["angle_distortion"], rel=1e-4)
    assert figures["angle_distortion"] < 1.5  # measured 1.31


def test_uv_command_relax_keeps_islands_and_lowers_distortion(program, fandisk):
    source, polycube, folder = fandisk
    figures = []
    for extra in ([], ["--relax"]):
        result = run(program, "uv", source, polycube, "--output", folder / "uv.obj", *extra)
        assert result.returncode == 0, result.stderr
        figures.append(json.loads(result.stdout))
    plain, relaxed = figures
    assert relaxed["islands"] == plain["islands"] and relaxed["flipped"] == 0
    assert relaxed["angle_distortion"] < 1.01 < plain["angle_distortion"]  # measured 1.0009 and 1.31
    assert relaxed["collapsed_area"] == 0.0


def test_uv_command_merge_gives_fewer_islands_and_shorter_seams(program, fandisk):
    source, polycube, folder = fandisk
    result = run(program, "uv", source, polycube, "--output", folder / "uv.obj", "--relax")
    relaxed = json.loads(result.stdout)
    result = run(program, "uv", source, polycube, "--output", folder / "uv.obj", "--merge", 0.01)
    assert result.returncode == 0, result.stderr
    merged = json.loads(result.stdout)
    # Measured: 21 islands -> 8, seams 15.2 -> 10.4, angle distortion 1.0009 -> 1.0016.
    assert merged["islands"] <= 10 < relaxed["islands"]
    assert merged["seam_length"] < 0.8 * relaxed["seam_length"]
    assert merged["flipped"] == 0 and merged["angle_distortion"] < relaxed["angle_distortion"] + 0.01
    assert merged["area_distortion"] < relaxed["area_distortion"] + 0.02


def test_polycube_uv_islands_are_the_charts(native, fandisk):
    source, polycube, _ = fandisk
    vertices, indices, sizes = native.read_mesh(str(source))
    positions = native.read_mesh(str(polycube))[0]
    unpacked = native.polycube_uv(vertices, indices, sizes, positions, pack=False)
    packed = native.polycube_uv(vertices, indices, sizes, positions)
    assert unpacked["islands"] == packed["islands"] == native.uv_figures(vertices, indices, sizes, packed["uvs"])["islands"]
    # Unpacked, every corner is its polycube vertex in the chart's plane.
    labels = unpacked["label_of_face"]
    corner_face = np.repeat(np.arange(len(sizes)), sizes)
    axis = labels[corner_face] // 2
    u = np.where(labels[corner_face] % 2 == 0, (axis + 1) % 3, (axis + 2) % 3)
    assert np.array_equal(unpacked["uvs"][:, 0], positions[indices, u])
    # Packed: islands' boxes do not overlap.
    island = packed["island_of_face"][corner_face]
    boxes = [(packed["uvs"][island == i].min(0), packed["uvs"][island == i].max(0)) for i in range(packed["islands"])]
    for i, (lo, hi) in enumerate(boxes):
        for lo2, hi2 in boxes[i + 1:]:
            assert np.any(hi <= lo2) or np.any(hi2 <= lo)


def test_remesh_command_writes_quads(program, native, fandisk):
    source, polycube, folder = fandisk
    out = folder / "fandisk-quads.obj"
    result = run(program, "remesh", source, polycube, "--edge-length", 0.02, "--output", out)
    assert result.returncode == 0, result.stderr
    summary = json.loads(result.stdout)
    vertices, indices, sizes = native.read_mesh(str(out))
    assert np.all(sizes == 4) and len(sizes) == summary["quads"]
    assert summary["open_edges"] == 0
    assert summary["irregular_vertices"] < 0.05 * len(vertices)


def test_quad_remesh_from_python_matches_the_program(native, fandisk):
    source, polycube, _ = fandisk
    vertices, indices, sizes = native.read_mesh(str(source))
    positions = native.read_mesh(str(polycube))[0]
    result = native.quad_remesh(vertices, indices, sizes, positions, edge_length=0.02)
    assert np.all(result["face_sizes"] == 4)
    assert result["source_face"].min() >= 0 and result["source_face"].max() < len(sizes)
    edges = np.stack([result["face_indices"].reshape(-1, 4), np.roll(result["face_indices"].reshape(-1, 4), -1, 1)], -1)
    directed = {tuple(e) for e in edges.reshape(-1, 2)}
    assert len(directed) == edges.shape[0] * 4  # each directed edge once
    assert all((b, a) in directed for a, b in directed)  # closed


def test_remesh_relax_moves_vertices_along_the_surface_only(program, native, fandisk):
    """--relax 0 keeps the grid as carried back; the default evens it out where it is stretched:
    the same quads, some vertices moved, the longest edge shorter."""
    source, polycube, folder = fandisk
    meshes = []
    for relax in ([], ["--relax", 0]):
        out = folder / f"relax{len(relax)}.obj"
        result = run(program, "remesh", source, polycube, "--edge-length", 0.02, "--output", out, *relax)
        assert result.returncode == 0, result.stderr
        meshes.append(native.read_mesh(str(out)))
    (relaxed, indices, _), (carried, carried_indices, _) = meshes
    assert np.array_equal(indices, carried_indices)
    moved = np.linalg.norm(relaxed - carried, axis=1) > 1e-9
    assert 0 < moved.sum() < len(relaxed)

    def longest(v):
        q = v[indices.reshape(-1, 4)]
        return np.linalg.norm(q - np.roll(q, -1, 1), axis=2).max()
    assert longest(relaxed) < longest(carried)
    bad = run(program, "remesh", source, polycube, "--edge-length", 0.02, "--output", folder / "x.obj", "--relax", -1)
    assert bad.returncode != 0 and "--relax" in bad.stderr


@pytest.mark.parametrize("case, message", [
    ("too_large", "larger than the model"),
    ("flipped", "flipped face"),
    ("not_polycube", "not exact"),
    ("other_mesh", "does not have the faces"),
])
def test_bad_input_gives_one_clear_line(program, fandisk, tmp_path, case, message):
    source, polycube, _ = fandisk
    out = tmp_path / "out.obj"
    args = [source, polycube, "--edge-length", 0.02]
    if case == "too_large":
        args[3] = 100
    elif case == "flipped":
        result = run(program, "label", source, "--output", tmp_path / "labels.txt")
        assert result.returncode == 0, result.stderr
        text = (tmp_path / "labels.txt").read_text()
        flipped = [str(int(line) ^ 1) for line in text.splitlines() if line and not line.startswith("#")]
        (tmp_path / "flipped.txt").write_text("\n".join(flipped) + "\n")
        args += ["--labels", tmp_path / "flipped.txt"]
    elif case == "not_polycube":
        args[1] = source
    elif case == "other_mesh":
        args[1] = MESHES / "eight.off"  # libcgal-demo, there whenever fandisk is
    result = run(program, "remesh", *args, "--output", out)
    assert result.returncode == 1
    assert message in result.stderr and result.stderr.count("\n") == 1, result.stderr
    assert not out.exists()
