"""The command-line script in the package: inputs of every kind, outputs, exit status."""

import json
import os
import re
import subprocess
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    MESHES, arrays, enable_addon, labelled_sphere, nearest_axis_labels, run_tests, scratch_folder,
    uv_sphere)

polycube = enable_addon()
HEADLESS = os.path.join(os.path.dirname(polycube.__file__), "headless.py")
TMP = scratch_folder("headless")


def _headless(*arguments):
    done = subprocess.run(
        [bpy.app.binary_path, "-b", "--factory-startup", "--python", HEADLESS, "--", *arguments],
        capture_output=True, text=True, timeout=600)
    print(done.stdout[-3000:], done.stderr[-3000:])
    return done


def _saved_objects(path):
    """Objects of a saved .blend, appended into this session."""
    with bpy.data.libraries.load(path) as (source, target):
        names = list(source.objects)
        target.objects = list(names)  # Blender fills this list in place
    # Appended objects are renamed when this session has one of the same name.
    return dict(zip(names, target.objects))


def _key_names(obj):
    return [block.name for block in obj.data.shape_keys.key_blocks] if obj.data.shape_keys else []


def _write_off(path, mesh):
    with open(path, "w") as file:
        file.write(f"OFF\n# a comment\n{len(mesh.vertices)} {len(mesh.face_sizes)} 0\n")
        np.savetxt(file, mesh.vertices, fmt="%.9g")
        start = 0
        for size in mesh.face_sizes:
            corners = mesh.face_indices[start:start + size]
            file.write(f"{size} {' '.join(map(str, corners))}\n")
            start += size


def _write_obj(path, mesh):
    with open(path, "w") as file:
        for vertex in mesh.vertices:
            file.write("v %.9g %.9g %.9g\n" % tuple(vertex))
        start = 0
        for size in mesh.face_sizes:
            corners = mesh.face_indices[start:start + size] + 1
            file.write("f " + " ".join(map(str, corners)) + "\n")
            start += size


def _write_ply(path, mesh):
    with open(path, "w") as file:
        file.write(f"ply\nformat ascii 1.0\nelement vertex {len(mesh.vertices)}\n"
                   "property float x\nproperty float y\nproperty float z\n"
                   f"element face {len(mesh.face_sizes)}\nproperty list uchar int vertex_indices\n"
                   "end_header\n")
        np.savetxt(file, mesh.vertices, fmt="%.9g")
        start = 0
        for size in mesh.face_sizes:
            file.write(f"{size} {' '.join(map(str, mesh.face_indices[start:start + size]))}\n")
            start += size


def _write_stl(path, mesh):
    with open(path, "w") as file:
        file.write("solid ball\n")
        start = 0
        for size in mesh.face_sizes:
            corners = mesh.face_indices[start:start + size]
            start += size
            for j in range(1, size - 1):  # STL holds triangles only
                file.write("facet normal 0 0 0\nouter loop\n")
                for v in (corners[0], corners[j], corners[j + 1]):
                    file.write("vertex %.9g %.9g %.9g\n" % tuple(mesh.vertices[v]))
                file.write("endloop\nendfacet\n")
        file.write("endsolid ball\n")


def _non_white_columns(path):
    image = bpy.data.images.load(path)
    try:
        width, height = image.size
        pixels = np.empty(width * height * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
        rgb = pixels.reshape(height, width, 4)[:, :, :3]
        return width, height, (rgb < 0.9).any(axis=(0, 2))
    finally:
        bpy.data.images.remove(image)


def test_off_input_with_output_preview_and_report():
    mesh = arrays(uv_sphere())
    off = os.path.join(TMP, "ball.off")
    _write_off(off, mesh)
    out, png, js = (os.path.join(TMP, name) for name in ("ball.blend", "ball.png", "ball.json"))
    done = _headless("--input", off, "--iterations", "200", "--animate", "--start-frame", "5",
                     "--output", out, "--preview", png, "--report", js)
    assert done.returncode == 0, done.stderr
    assert "normal deviation  max" in done.stdout and "converged" in done.stdout

    with open(js) as file:
        figures = json.load(file)["ball"]
    assert figures["converged"] is True and figures["normal_deviation_max_deg"] < 0.5
    assert figures["flipped_faces"] == 0 and figures["animation_frames"][0] == 5

    ball = _saved_objects(out)["ball"]
    names = _key_names(ball)
    assert names == ["Basis"] + [f"Polycube {k:03d}" for k in range(1, figures["iterations"] + 1)]
    assert ball["polycube_report"]["iterations"] == figures["iterations"]
    coordinates = np.empty(len(ball.data.vertices) * 3, dtype=np.float32)
    ball.data.vertices.foreach_get("co", coordinates)
    assert np.allclose(coordinates.reshape(-1, 3), mesh.vertices, atol=1e-6)

    # The preview shows two shapes side by side on a light background.
    width, height, ink = _non_white_columns(png)
    assert (width, height) == (1600, 800)
    assert ink[: width // 2].sum() > width // 8 and ink[width // 2:].sum() > width // 8
    assert not ink[:20].any() and not ink[-20:].any()


def test_obj_input_with_a_label_file_keeps_file_coordinates():
    sphere = uv_sphere()
    mesh = arrays(sphere)
    labels = nearest_axis_labels(sphere)
    obj_path, label_path = os.path.join(TMP, "ball.obj"), os.path.join(TMP, "ball.labels")
    _write_obj(obj_path, mesh)
    np.savetxt(label_path, labels, fmt="%d")
    out, js = os.path.join(TMP, "obj.blend"), os.path.join(TMP, "obj.json")
    done = _headless("--input", obj_path, "--labels", label_path, "--iterations", "200",
                     "--keep", "final", "--output", out, "--report", js)
    assert done.returncode == 0, done.stderr
    with open(js) as file:
        (figures,) = json.load(file).values()
    assert figures["label_source"] == "attribute polycube_label"
    assert figures["unlabelled_faces"] == 0 and figures["converged"] is True
    (ball,) = _saved_objects(out).values()
    assert len(_key_names(ball)) == 2
    coordinates = np.empty(len(ball.data.vertices) * 3, dtype=np.float32)
    ball.data.vertices.foreach_get("co", coordinates)
    # Imported without axis conversion: labels are about the file's own axes.
    assert np.allclose(coordinates.reshape(-1, 3), mesh.vertices, atol=1e-6)


def test_ply_and_stl_inputs():
    mesh = arrays(uv_sphere())
    triangles = int((mesh.face_sizes - 2).sum())
    for extension, write, faces in (("ply", _write_ply, len(mesh.face_sizes)), ("stl", _write_stl, triangles)):
        path, js = os.path.join(TMP, f"ball.{extension}"), os.path.join(TMP, f"{extension}.json")
        write(path, mesh)
        done = _headless("--input", path, "--iterations", "200", "--report", js)
        assert done.returncode == 0, done.stderr
        with open(js) as file:
            (figures,) = json.load(file).values()
        # The same surface, its vertices shared between faces (STL repeats them per facet).
        assert (figures["vertices"], figures["faces"]) == (len(mesh.vertices), faces), (extension, figures)
        assert figures["converged"] is True and figures["flipped_faces"] == 0, (extension, figures)


def test_automatic_labels_and_subdivide_before():
    bpy.ops.mesh.primitive_cube_add()
    cube = arrays(bpy.context.active_object)
    off, out, js = (os.path.join(TMP, name) for name in ("box.off", "box.blend", "box.json"))
    _write_off(off, cube)
    done = _headless("--input", off, "--labels", "auto", "--subdivide", "2", "--scheme", "catmark",
                     "--iterations", "200", "--output", out, "--report", js)
    assert done.returncode == 0, done.stderr
    with open(js) as file:
        figures = json.load(file)
    assert list(figures) == ["box polycube"], list(figures)
    result = figures["box polycube"]
    assert result["faces"] == 6 * 4 ** 2 and result["subdivided_from"] == "box"
    assert result["label_source"] == "attribute polycube_label, subdivided (catmark x2)"
    assert result["converged"] is True and result["flipped_faces"] == 0, result
    saved = _saved_objects(out)
    assert len(saved["box"].data.vertices) == 8 and _key_names(saved["box"]) == []
    # The automatic labels were written to the input object, as the Auto Label operator does.
    assert "polycube_label" in saved["box"].data.attributes and len(saved["box"].face_maps) == 6
    assert len(_key_names(saved["box polycube"])) == result["iterations"] + 1


def test_blend_input_deforms_only_the_named_objects():
    labelled_sphere("Ball")
    labelled_sphere("Other", location=(4, 0, 0))
    source = os.path.join(TMP, "two.blend")
    bpy.ops.wm.save_as_mainfile(filepath=source, copy=True)
    out = os.path.join(TMP, "two-out.blend")
    done = _headless("--input", source, "--objects", "Ball", "--iterations", "50", "--output", out)
    assert done.returncode == 0, done.stderr
    saved = _saved_objects(out)
    assert len(_key_names(saved["Ball"])) > 1 and "polycube_report" in saved["Ball"].keys()
    assert _key_names(saved["Other"]) == [] and "polycube_report" not in saved["Other"].keys()


def test_demo_model_when_no_input_is_given():
    js = os.path.join(TMP, "demo.json")
    done = _headless("--report", js)
    assert done.returncode == 0, done.stderr
    with open(js) as file:
        (figures,) = json.load(file).values()
    assert figures["label_source"] == "face maps" and figures["converged"] is True


def test_fandisk_off_from_libcgal_demo():
    done = _headless("--input", os.path.join(MESHES, "fandisk.off"), "--iterations", "20")
    assert done.returncode == 0, done.stderr
    assert re.search(r"fandisk: \d+ iterations, converged", done.stdout), done.stdout
    assert "6475 vertices, 12946 faces" in done.stdout and "flipped faces 0" in done.stdout


def test_uv_and_remesh_of_every_deformed_object():
    # fandisk (libcgal-demo) with automatic labels: the UV map comes first, so the
    # quads carry it; both are saved with the .blend and named in the report.
    out, js = os.path.join(TMP, "uses.blend"), os.path.join(TMP, "uses.json")
    done = _headless("--input", os.path.join(MESHES, "fandisk.off"), "--labels", "auto", "--iterations", "200",
                     "--uv", "merged", "--remesh", "1500", "--output", out, "--report", js)
    assert done.returncode == 0, done.stderr
    assert re.search(r"UV map 'Polycube', \d+ islands", done.stdout), done.stdout
    assert re.search(r"'fandisk quads': \d+ quads, 38 irregular vertices", done.stdout), done.stdout
    with open(js) as file:
        report = json.load(file)["fandisk"]
    assert report["uv"] == {"map": "Polycube", "kind": "merged"}
    assert report["remesh"]["object"] == "fandisk quads" and abs(report["remesh"]["faces"] - 1500) < 150

    saved = _saved_objects(out)
    fandisk, quads = saved["fandisk"], saved["fandisk quads"]
    assert fandisk.data.uv_layers.active.name == "Polycube"
    sizes = np.empty(len(quads.data.polygons), dtype=np.int32)
    quads.data.polygons.foreach_get("loop_total", sizes)
    assert len(sizes) == report["remesh"]["faces"] and (sizes == 4).all()
    assert "Polycube" in quads.data.uv_layers

    # A polycube the remesh refuses (not exact) fails the run, and nothing is written.
    refused_out = os.path.join(TMP, "refused.blend")
    refused = _headless("--input", os.path.join(MESHES, "elephant.off"), "--iterations", "3", "--remesh", "500",
                        "--output", refused_out)
    _failing(refused, 1, "nothing written")
    assert not os.path.exists(refused_out)
    few = _headless("--remesh", "2")
    _failing(few, 2, "--remesh takes a number of quads of at least 6")


def test_labels_that_cannot_be_flattened_get_advice():
    # The elephant's nearest-axis labels: flattening would leave folds and crush a
    # sixth of it (the last refused attempt: 570 folds, 16%).
    done = _headless("--input", os.path.join(MESHES, "elephant.off"), "--iterations", "40")
    assert done.returncode == 0, done.stderr
    assert re.search(r"not converged|no progress", done.stdout) and "flipped faces 0" in done.stdout, done.stdout
    match = re.search(r"Flat charts would (?:leave \d+ folded faces \(and )?collapse (\d+)% of the surface",
                      done.stdout)
    assert match and int(match.group(1)) > 10, done.stdout
    assert "Every face took its nearest axis: try Auto Label" in done.stdout


def test_bad_input_gives_a_message_and_a_failing_status():
    missing = _headless("--input", os.path.join(TMP, "nothing.off"))
    assert missing.returncode != 0 and "no such file" in missing.stderr
    junk = os.path.join(TMP, "junk.off")
    with open(junk, "w") as file:
        file.write("OFF\n3 1 0\n0 0 0\n1 0 0\n")
    broken = _headless("--input", junk)
    assert broken.returncode != 0 and "junk.off line 2" in broken.stderr and "truncated" in broken.stderr
    flat = os.path.join(TMP, "flat.off")
    with open(flat, "w") as file:
        file.write("OFF\n3 1 0\n0 0 0\n0 0 0\n0 0 0\n3 0 1 2\n")
    refused = _headless("--input", flat)
    assert refused.returncode != 0 and "zero area" in refused.stderr
    labels = os.path.join(TMP, "short.labels")
    np.savetxt(labels, [0, 1], fmt="%d")
    short = _headless("--labels", labels)
    assert short.returncode != 0 and "2 labels" in short.stderr



def _files(folder):
    return sorted(os.listdir(folder)) if os.path.isdir(folder) else None


def _failing(done, status, message):
    assert done.returncode == status, (done.returncode, done.stderr)
    assert message in done.stderr, done.stderr
    assert "Wrote" not in done.stdout, done.stdout


def test_outputs_all_or_none():
    folder = os.path.join(TMP, "outputs")
    os.makedirs(folder, exist_ok=True)
    out, js, png = (os.path.join(folder, name) for name in ("ball.blend", "ball.json", "ball.png"))
    # The report cannot be written (its folder is a file): the .blend staged before it goes too.
    with open(os.path.join(folder, "file"), "w") as file:
        file.write("in the way")
    _failing(_headless("--iterations", "5", "--output", out, "--report", os.path.join(folder, "file", "r.json")),
             1, f"cannot write {os.path.join(folder, 'file', 'r.json')}: Not a directory")
    assert _files(folder) == ["file"]
    # Blender cannot save there: a non-zero status, not a traceback with status 0; the
    # folder made for the report is removed again.
    _failing(_headless("--iterations", "5", "--output", "/proc/x.blend", "--report",
                       os.path.join(folder, "new", "r.json")), 1, "cannot write /proc/x.blend")
    assert _files(folder) == ["file"]
    _failing(_headless("--iterations", "5", "--report", js, "--preview", folder), 1,
             f"cannot write {folder}: it is a directory")
    assert _files(folder) == ["file"]
    # An old file at a target keeps its contents on failure and is replaced on success.
    with open(js, "w") as file:
        file.write("old")
    _failing(_headless("--iterations", "5", "--report", js, "--output", os.path.join(folder, "file", "x.blend")),
             1, "Not a directory")
    with open(js) as file:
        assert file.read() == "old"
    done = _headless("--iterations", "5", "--report", js, "--output", out, "--preview", png)
    assert done.returncode == 0, done.stderr
    assert _files(folder) == ["ball.blend", "ball.json", "ball.png", "file"]
    with open(js) as file:
        assert json.load(file)["Sphere"]["iterations"] == 5


def test_standard_output_that_cannot_be_written_fails_and_writes_nothing():
    folder = os.path.join(TMP, "full")
    os.makedirs(folder, exist_ok=True)
    with open("/dev/full", "w") as full:
        done = subprocess.run(
            [bpy.app.binary_path, "-b", "--factory-startup", "--python", HEADLESS, "--", "--iterations", "3",
             "--report", os.path.join(folder, "r.json")],
            stdout=full, stderr=subprocess.PIPE, text=True, timeout=600)
    assert done.returncode == 1, done.stderr
    assert "polycube: cannot write to standard output: No space left on device; nothing written" in done.stderr
    assert _files(folder) == []


def test_inputs_the_command_line_program_would_refuse():
    folder = os.path.join(TMP, "refused")
    os.makedirs(folder, exist_ok=True)
    out = os.path.join(folder, "out.blend")
    mesh = arrays(uv_sphere())
    whole = os.path.join(folder, "whole.obj")
    _write_obj(whole, mesh)
    with open(whole) as file:
        text = file.read()
    truncated = os.path.join(folder, "truncated.obj")
    with open(truncated, "w") as file:
        file.write(text[: text.rindex("\nf ") + 5])  # the last face cut after one corner
    _failing(_headless("--input", truncated, "--output", out), 2, "truncated.obj line")
    _failing(_headless("--input", folder, "--output", out), 2, f"{folder} is a directory")
    labels = os.path.join(folder, "float.labels")
    np.savetxt(labels, np.full(len(mesh.face_sizes), 2.7), fmt="%.1f")
    _failing(_headless("--input", whole, "--labels", labels, "--output", out), 2,
             "line 1: expected an integer label, got '2.7'")
    _failing(_headless("--input", whole, "--subdivide", "9", "--output", out), 2, "--subdivide must be 0..8, got 9")
    # Auto Label failing (an object with no faces) fails the run instead of deforming without it.
    empty = bpy.data.objects.new("Nothing", bpy.data.meshes.new("Nothing"))
    bpy.context.scene.collection.objects.link(empty)
    source = os.path.join(folder, "nothing.blend")
    bpy.ops.wm.save_as_mainfile(filepath=source, copy=True)
    bpy.data.objects.remove(empty)
    _failing(_headless("--input", source, "--objects", "Nothing", "--labels", "auto", "--output", out), 1,
             "'Nothing'")
    assert _files(folder) == ["float.labels", "nothing.blend", "truncated.obj", "whole.obj"]


run_tests(globals())
