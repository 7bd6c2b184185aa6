"""Uses of the polycube in Blender: Polycube UV (a UV map "Polycube", one island per
chart, packed apart) and Polycube Remesh (a new all-quad object on the surface), and
their refusals: no run yet, a flipped polycube, an edge length larger than the model."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    MESHES, arrays, deform, enable_addon, labelled_sphere, off_object, run_tests, select_only, vertices)

polycube = enable_addon()
native = polycube.polycube_native


def _uvs(obj, name="Polycube"):
    """Per corner, in read_mesh_arrays order (the loops, for these meshes)."""
    layer = obj.data.uv_layers[name]
    flat = np.empty(2 * len(obj.data.loops), dtype=np.float32)
    layer.data.foreach_get("uv", flat)
    return flat.reshape(-1, 2).astype(np.float64)


def _error(operator, **settings):
    try:
        operator(**settings)
    except RuntimeError as error:
        return str(error)
    raise AssertionError("the operator reported no error")


def _deformed_fandisk():
    obj = off_object(os.path.join(MESHES, "fandisk.off"))
    assert deform(obj, iterations=200, label_source='AUTO') == {'FINISHED'}
    assert polycube.report.load_report(obj)["converged"]
    return obj


def test_uv_map_one_island_per_chart_packed_apart():
    sphere = labelled_sphere()
    sphere.data.uv_layers.new(name="Mine")
    assert deform(sphere, iterations=200) == {'FINISHED'}
    assert bpy.ops.object.polycube_uv() == {'FINISHED'}
    assert sphere.data.uv_layers.active.name == "Polycube"
    assert "Mine" in sphere.data.uv_layers  # the user's UV map is kept
    mesh, uvs = arrays(sphere), _uvs(sphere)
    figures = native.uv_figures(mesh.vertices, mesh.face_indices, mesh.face_sizes, uvs)
    # Nearest-axis labels on a sphere: six charts, six islands, none turned over.
    assert figures["islands"] == 6 and figures["flipped"] == 0, figures
    assert figures["angle_distortion"] < 1.5, figures  # measured 1.32
    assert uvs.min() >= 0.0 and uvs.max() <= 1.0
    # Islands' boxes apart: islands are the faces joined where UVs agree; compare boxes pairwise.
    result = native.polycube_uv(mesh.vertices, mesh.face_indices, mesh.face_sizes,
                                polycube.polycube_shape.polycube_of(sphere)[1])
    island = np.repeat(result["island_of_face"], mesh.face_sizes)
    boxes = [(uvs[island == i].min(0), uvs[island == i].max(0)) for i in range(result["islands"])]
    for i, (lo, hi) in enumerate(boxes):
        for lo2, hi2 in boxes[i + 1:]:
            assert np.any(hi <= lo2 + 1e-6) or np.any(hi2 <= lo + 1e-6)


def test_conformal_uv_map_keeps_the_islands():
    sphere = labelled_sphere()
    assert deform(sphere, iterations=200) == {'FINISHED'}
    mesh = arrays(sphere)
    figures = []
    for relax in (False, True):
        assert bpy.ops.object.polycube_uv(relax=relax) == {'FINISHED'}
        figures.append(native.uv_figures(mesh.vertices, mesh.face_indices, mesh.face_sizes, _uvs(sphere)))
    assert [layer.name for layer in sphere.data.uv_layers].count("Polycube") == 1  # refilled, not a second map
    plain, relaxed = figures
    assert relaxed["islands"] == plain["islands"] == 6 and relaxed["flipped"] == 0
    assert relaxed["angle_distortion"] < 1.1 < plain["angle_distortion"], figures
    assert bpy.ops.object.polycube_uv(merge=True) == {'FINISHED'}
    merged = native.uv_figures(mesh.vertices, mesh.face_indices, mesh.face_sizes, _uvs(sphere))
    assert merged["islands"] <= 6 and merged["flipped"] == 0 and merged["angle_distortion"] < 1.1, merged


def test_remesh_makes_a_new_all_quad_object_on_the_surface():
    fandisk = _deformed_fandisk()
    material = bpy.data.materials.new("Paint")
    fandisk.data.materials.append(material)
    before = vertices(fandisk)
    assert bpy.ops.object.polycube_remesh(mode='FACES', target_faces=3000) == {'FINISHED'}
    quads = bpy.context.active_object
    assert quads is not fandisk and quads.name == "fandisk quads"
    assert np.array_equal(vertices(fandisk), before)
    data = quads.data
    sizes = np.empty(len(data.polygons), dtype=np.int32)
    data.polygons.foreach_get("loop_total", sizes)
    assert np.all(sizes == 4)
    assert 2850 <= len(data.polygons) <= 3150, len(data.polygons)  # Target Faces within 5%
    # Closed and manifold: every edge in two faces.
    counts = {}
    for polygon in data.polygons:
        for key in polygon.edge_keys:
            counts[key] = counts.get(key, 0) + 1
    assert set(counts.values()) == {2}
    assert len(counts) == len(data.edges)
    assert data.materials[0] == material
    assert quads.matrix_world == fandisk.matrix_world


def test_remesh_lays_an_open_boundary_along_the_grid():
    # A flat disk is its own polycube (one +Z chart): its round rim becomes a rectangle of grid
    # lines, whose 4 corners are the only irregular vertices (a staircase has two a step).
    bpy.ops.mesh.primitive_circle_add(vertices=64, fill_type='TRIFAN')
    disk = bpy.context.active_object
    for vertex in disk.data.vertices:  # a gentle saddle for the solver to flatten
        vertex.co.z = 0.1 * vertex.co.x * vertex.co.y
    select_only(disk)
    assert deform(disk, iterations=50) == {'FINISHED'}
    assert bpy.ops.object.polycube_remesh(mode='FACES', target_faces=400) == {'FINISHED'}
    data = bpy.context.active_object.data
    counts, valence = {}, np.zeros(len(data.vertices), dtype=int)
    for polygon in data.polygons:
        assert polygon.loop_total == 4
        for key in polygon.edge_keys:
            counts[key] = counts.get(key, 0) + 1
    on_boundary = np.zeros(len(data.vertices), dtype=bool)
    for (a, b), uses in counts.items():
        valence[[a, b]] += 1
        if uses == 1:
            on_boundary[[a, b]] = True
    assert on_boundary.sum() > 40
    irregular = np.where(on_boundary, valence != 3, valence != 4)
    assert irregular.sum() == 4, irregular.sum()
    assert np.all(valence[irregular] == 2)


def test_remesh_carries_uv_maps():
    sphere = labelled_sphere()  # Blender's UV sphere comes with its UV map "UVMap": u around, v up
    assert deform(sphere, iterations=200) == {'FINISHED'}
    assert bpy.ops.object.polycube_remesh(mode='FACES', target_faces=2000) == {'FINISHED'}
    quads = bpy.context.active_object
    assert quads.data.uv_layers.active.name == "UVMap"
    flat = np.empty(2 * len(quads.data.loops), dtype=np.float32)
    quads.data.uv_layers["UVMap"].data.foreach_get("uv", flat)
    uv = flat.reshape(-1, 2)
    loops = np.empty(len(quads.data.loops), dtype=np.int32)
    quads.data.loops.foreach_get("vertex_index", loops)
    z = vertices(quads)[loops, 2]
    # The sphere's v runs from the south pole (0) to the north pole (1): v follows the height.
    assert np.corrcoef(uv[:, 1], z)[0, 1] > 0.99


def test_remesh_target_edge_length():
    fandisk = _deformed_fandisk()
    assert bpy.ops.object.polycube_remesh(mode='EDGE_LENGTH', edge_length=0.04) == {'FINISHED'}
    quads = bpy.context.active_object
    co = vertices(quads)
    lengths = [np.linalg.norm(co[a] - co[b]) for a, b in (e.vertices for e in quads.data.edges)]
    assert 0.025 < np.median(lengths) < 0.06, np.median(lengths)


def test_remesh_relax_keeps_the_quads_and_moves_vertices_on_the_surface():
    fandisk = _deformed_fandisk()
    results = []
    for relax in (0, 10):
        select_only(fandisk)
        assert bpy.ops.object.polycube_remesh(mode='FACES', target_faces=3000, relax=relax) == {'FINISHED'}
        quads = bpy.context.active_object
        loops = np.empty(len(quads.data.loops), dtype=np.int32)
        quads.data.loops.foreach_get("vertex_index", loops)
        results.append((vertices(quads), loops))
    (carried, loops0), (relaxed, loops1) = results
    assert np.array_equal(loops0, loops1)
    moved = np.linalg.norm(relaxed - carried, axis=1) > 1e-6
    assert 0 < moved.sum() < len(carried), moved.sum()


def test_clear_refusals():
    sphere = labelled_sphere()
    select_only(sphere)
    # No run yet: the buttons are off, and say why.
    assert not bpy.ops.object.polycube_uv.poll() and not bpy.ops.object.polycube_remesh.poll()
    assert "Deform the active mesh to its polycube first" in _error(bpy.ops.object.polycube_uv)
    assert deform(sphere, iterations=200) == {'FINISHED'}
    message = _error(bpy.ops.object.polycube_remesh, mode='EDGE_LENGTH', edge_length=100.0)
    assert "larger than the model" in message, message
    # A polycube facing away from the labels it was made for: flipped faces.
    sphere[polycube.report.LABELS_USED_PROPERTY] = polycube.report.load_labels_used(sphere) ^ 1
    for operator in (bpy.ops.object.polycube_uv, bpy.ops.object.polycube_remesh):
        message = _error(operator)
        assert "flipped face" in message, message
    assert "Polycube" not in sphere.data.uv_layers
    assert len(bpy.data.objects) == 1


run_tests(globals())
