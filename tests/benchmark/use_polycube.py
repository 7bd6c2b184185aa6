#!/usr/bin/env python3
"""Uses of the polycube against Blender's own tools, on the models that become exact
polycubes: our quad remesh against QuadriFlow (`object.quadriflow_remesh`) at the same
face count, our polycube UVs against Smart UV Project (`uv.smart_project`).

    /usr/bin/python3 tests/benchmark/use_polycube.py [--faces 3000] [--models fandisk,B0,...] [--detail D]

Runs itself inside `blender -b`; polycubes come from `build/polycube deform --labels auto`
(B0: its published labels). Prints two Markdown tables and writes build/bench/use/results.json.
Our spacing is set so that our quad count is nearest QuadriFlow's (it only aims at a target).
Figures: quads share, regular vertices (valence 4 inside, 3 on a boundary: both meshes counted
alike) share and the irregular count (how many of them on an open boundary); Hausdorff distance
to the input (both ways, sampled at vertices, edge midpoints and face centres) over the input's
bounding-box diagonal; manifold
and closed (every edge in two faces, walked once each way); UV angle and area distortion
(area-weighted means of each triangle's singular value ratio and of max(r, 1/r), r its UV area
share over its area share), islands, seam length.
"""
import json
import os
import pathlib
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / "build"
MESHES = BUILD / "data" / "meshes"
SHARED = ROOT.parent / "shared" / "data"
OUT = BUILD / "bench" / "use"

# (name, mesh file or Blender primitive, labels for `polycube deform`)
MODELS = [
    ("sphere", "primitive:uv_sphere", "auto"),
    ("fandisk", MESHES / "fandisk.off", "auto"),
    ("B0", SHARED / "B0" / "surface.obj", SHARED / "B0" / "labeling.txt"),
    ("bone", SHARED / "bone" / "surface.obj", "auto"),
    ("eight", MESHES / "eight.off", "auto"),
    ("suzanne", "primitive:monkey", "auto"),
    ("bear", MESHES / "bear.off", "auto"),
    ("mushroom", MESHES / "mushroom.off", "auto"),
    ("mech-holes-shark", MESHES / "mech-holes-shark.off", "auto"),
    ("handle", MESHES / "handle.off", "auto"),
    ("joint", MESHES / "joint.off", "auto"),
    ("cactus", MESHES / "cactus.off", "auto"),
]


def outside_blender():
    import argparse
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--faces", type=int, default=3000, help="quads to aim for (QuadriFlow gets ours)")
    parser.add_argument("--models", default=",".join(name for name, _, _ in MODELS))
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--pictures", default="", help="folder for the README's pictures (fandisk, suzanne)")
    parser.add_argument("--detail", type=float, default=0.5,
                        help="the automatic labels' detail (0..1; lower: fewer charts, fewer polycube corners)")
    args = parser.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    command = [args.blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", __file__, "--",
               "--faces", str(args.faces), "--models", args.models, "--detail", str(args.detail),
               "--pictures", os.path.abspath(args.pictures) if args.pictures else ""]
    result = subprocess.run(command, capture_output=True, text=True)
    tables = [line[len("TABLE "):] for line in result.stdout.splitlines() if line.startswith("TABLE ")]
    print("\n".join(tables))
    if result.returncode != 0:
        sys.stderr.write(result.stdout[-4000:] + result.stderr[-4000:])
        sys.exit(result.returncode)


# ------------------------------------------------------------------ inside Blender

PICTURED = ("fandisk", "suzanne")


def render_pictures(shown, folder):
    """remesh.png: our quads beside QuadriFlow's, a row per model; uv-checker.png: a checker
    texture on our polycube UVs. Workbench renders, edges drawn by a wireframe copy."""
    import bpy
    from mathutils import Vector
    folder.mkdir(parents=True, exist_ok=True)
    rows = [shown[name] for name in PICTURED if name in shown]
    checker = bpy.data.images.new("checker", 1024, 1024)
    checker.generated_type = 'UV_GRID'
    material = bpy.data.materials.new("checker")
    material.use_nodes = True
    texture = material.node_tree.nodes.new("ShaderNodeTexImage")
    texture.image = checker
    material.node_tree.links.new(texture.outputs["Color"],
                                 material.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
    material.node_tree.nodes.active = texture
    for filename, grid, colour_type in (("remesh.png", [row[:2] for row in rows], 'OBJECT'),
                                       ("uv-checker.png", [[row[2] for row in rows]], 'TEXTURE')):
        scene = bpy.data.scenes.new(filename)
        view = Vector((0.6, -1.0, 0.7)).normalized()
        rotation = (-view).to_track_quat('-Z', 'Y')
        right, up = rotation @ Vector((1, 0, 0)), rotation @ Vector((0, 1, 0))
        for r, objects in enumerate(grid):
            for c, obj in enumerate(objects):
                corners = [obj.matrix_world @ Vector(corner) for corner in obj.bound_box]
                centre = sum(corners, Vector()) / 8
                size = max((a - b).length for a in corners for b in corners)
                obj.scale = (1.0 / size,) * 3
                obj.location = -centre / size + right * 0.8 * c - up * 0.8 * r
                scene.collection.objects.link(obj)
                obj.color = (0.85, 0.85, 0.85, 1.0)
                if colour_type == 'TEXTURE':
                    obj.data.materials.append(material)
                else:
                    wire = obj.copy()
                    wire.modifiers.new("wire", 'WIREFRAME').thickness = 0.0015 * size
                    wire.color = (0.05, 0.05, 0.05, 1.0)
                    scene.collection.objects.link(wire)
        camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
        camera.data.type = 'ORTHO'
        columns, lines = max(len(objects) for objects in grid), len(grid)
        aspect = (500 * columns) / (400 * lines)
        camera.data.ortho_scale = max(0.8 * columns, 0.8 * lines * aspect)
        camera.location = right * 0.4 * (columns - 1) - up * 0.4 * (lines - 1) + view * 10
        camera.rotation_euler = rotation.to_euler()
        scene.collection.objects.link(camera)
        scene.camera = camera
        scene.render.engine = 'BLENDER_WORKBENCH'
        scene.render.resolution_x, scene.render.resolution_y = 500 * columns, 400 * lines
        scene.render.filepath = str(folder / filename)
        scene.display.shading.light = 'STUDIO'
        scene.display.shading.color_type = colour_type
        scene.world = bpy.data.worlds.new(filename)
        scene.world.color = (1.0, 1.0, 1.0)
        scene.view_settings.view_transform = 'Standard'
        bpy.ops.render.render(write_still=True, scene=scene.name)

def inside_blender(argv):
    import bpy
    import numpy as np
    from mathutils.bvhtree import BVHTree
    sys.path.insert(0, str(BUILD))
    import polycube_native as native

    faces_wanted = int(argv[argv.index("--faces") + 1])
    wanted = argv[argv.index("--models") + 1].split(",")
    pictures = argv[argv.index("--pictures") + 1] if "--pictures" in argv else ""
    detail = argv[argv.index("--detail") + 1] if "--detail" in argv else "0.5"
    shown = {}  # model -> (our quads, QuadriFlow's, our UVs) objects, for the pictures

    def write_off(path, vertices, indices, sizes):
        lines = ["OFF", f"{len(vertices)} {len(sizes)} 0"] + ["%r %r %r" % tuple(v) for v in vertices]
        at = 0
        for k in sizes:
            lines.append(" ".join(map(str, [k, *indices[at:at + k]])))
            at += k
        pathlib.Path(path).write_text("\n".join(lines) + "\n")

    def mesh_arrays(obj):
        m = obj.data
        v = np.empty(3 * len(m.vertices)); m.vertices.foreach_get("co", v)
        sizes = np.empty(len(m.polygons), dtype=np.int32); m.polygons.foreach_get("loop_total", sizes)
        loops = np.empty(len(m.loops), dtype=np.int32); m.loops.foreach_get("vertex_index", loops)
        return v.reshape(-1, 3), loops, sizes

    def new_object(name, vertices, indices, sizes):
        mesh = bpy.data.meshes.new(name)
        mesh.vertices.add(len(vertices)); mesh.vertices.foreach_set("co", np.asarray(vertices, np.float32).ravel())
        mesh.loops.add(len(indices)); mesh.loops.foreach_set("vertex_index", np.asarray(indices, np.int32))
        mesh.polygons.add(len(sizes))
        mesh.polygons.foreach_set("loop_start", (np.cumsum(sizes) - sizes).astype(np.int32))
        if not bpy.types.MeshPolygon.bl_rna.properties["loop_total"].is_readonly:
            mesh.polygons.foreach_set("loop_total", np.asarray(sizes, np.int32))
        mesh.update(calc_edges=True)
        obj = bpy.data.objects.new(name, mesh)
        bpy.context.scene.collection.objects.link(obj)
        return obj

    def primitive(kind, path):
        bpy.ops.object.select_all(action='DESELECT')
        getattr(bpy.ops.mesh, f"primitive_{kind}_add")()
        obj = bpy.context.active_object
        if kind == "monkey":  # 500 faces are too coarse to bend: two levels of Catmull-Clark, as artists do
            modifier = obj.modifiers.new("subdivide", 'SUBSURF')
            modifier.levels = 2
            bpy.ops.object.modifier_apply(modifier=modifier.name)
        write_off(path, *mesh_arrays(obj))
        bpy.data.objects.remove(obj)

    def edges_of(indices, sizes):
        starts = np.cumsum(sizes) - sizes
        nxt = np.arange(len(indices)) + 1
        ends = np.cumsum(sizes)
        nxt[ends - 1] = starts
        return np.stack([indices, indices[nxt]], 1)

    def mesh_figures(vertices, indices, sizes, reference):
        directed = edges_of(indices, sizes)
        undirected, uses = np.unique(np.sort(directed, 1), axis=0, return_counts=True)
        oriented = len(np.unique(directed, axis=0)) == len(directed)
        valence = np.bincount(undirected.ravel(), minlength=len(vertices))
        on_boundary = np.zeros(len(vertices), dtype=bool)
        on_boundary[undirected[uses == 1].ravel()] = True
        used = valence > 0
        regular = np.where(on_boundary, valence == 3, valence == 4)
        ref_v, ref_i, ref_s = reference
        diagonal = np.linalg.norm(ref_v.max(0) - ref_v.min(0))
        return {
            "faces": int(len(sizes)), "vertices": int(used.sum()),
            "quads": float(np.mean(sizes == 4)), "valence4": float(np.mean(regular[used])),
            "irregular": int(np.sum(used & ~regular)), "irregular_boundary": int(np.sum(used & ~regular & on_boundary)),
            # inner vertices by valence: on a closed genus-0 quad mesh n3 - n5 - 2 n6 - ... = 8
            "valences": {int(k): int(c) for k, c in zip(*np.unique(valence[used & ~on_boundary], return_counts=True))},
            "manifold": bool(np.all(uses <= 2) and oriented), "open_edges": int(np.sum(uses == 1)),
            "hausdorff": hausdorff((vertices, indices, sizes), reference) / diagonal,
        }

    def irregular(figures):
        on_boundary = figures["irregular_boundary"]
        return f"{figures['irregular']}, {on_boundary} on the boundary" if on_boundary else str(figures["irregular"])

    def closed(figures):
        if not figures["manifold"]:
            return "no"
        return "yes" if figures["open_edges"] == 0 else f"{figures['open_edges']} open edges"

    def samples(vertices, indices, sizes):
        starts = np.cumsum(sizes) - sizes
        centres = np.add.reduceat(vertices[indices], starts) / sizes[:, None]
        e = edges_of(indices, sizes)
        return np.concatenate([vertices, centres, 0.5 * (vertices[e[:, 0]] + vertices[e[:, 1]])])

    def bvh(vertices, indices, sizes):
        starts = np.cumsum(sizes) - sizes
        polygons = [indices[s:s + k].tolist() for s, k in zip(starts, sizes)]
        return BVHTree.FromPolygons(vertices.tolist(), polygons, all_triangles=False)

    def one_way(points, tree):
        return max(tree.find_nearest(p)[3] for p in points.tolist())

    def hausdorff(a, b):
        return max(one_way(samples(*a), bvh(*b)), one_way(samples(*b), bvh(*a)))

    def corner_uvs(obj):
        flat = np.empty(2 * len(obj.data.loops), dtype=np.float32)
        obj.data.uv_layers.active.data.foreach_get("uv", flat)
        return flat.reshape(-1, 2).astype(np.float64)

    rows = []
    for name, source, labels in MODELS:
        if name not in wanted:
            continue
        mesh_path = OUT / f"{name}.off"
        if str(source).startswith("primitive:"):
            primitive(str(source).split(":")[1], mesh_path)
        else:
            mesh_path = pathlib.Path(source)
            if not mesh_path.exists():
                print(f"TABLE <!-- {name}: {mesh_path} is missing -->")
                continue
        polycube_path, report_path = OUT / f"{name}-polycube.obj", OUT / f"{name}-deform.json"
        start = time.perf_counter()
        subprocess.run([str(BUILD / "polycube"), "deform", str(mesh_path), "--labels", str(labels),
                        "--iterations", "200", "--detail", detail, "--output", str(polycube_path),
                        "--report", str(report_path)],
                       check=True, capture_output=True)
        seconds_deform = time.perf_counter() - start
        report = json.loads(report_path.read_text())
        row = {"model": name, "input_faces": report["faces"], "exact": bool(report["converged"]),
               "seconds_deform": seconds_deform}
        rows.append(row)
        if not row["exact"]:
            continue
        vertices, indices, sizes = native.read_mesh(str(mesh_path))
        positions = native.read_mesh(str(polycube_path))[0]
        reference = (vertices, indices, sizes)
        starts = np.cumsum(sizes) - sizes
        tri_area = 0.0
        for s, k in zip(starts, sizes):  # fan area per polygon
            p = vertices[indices[s:s + k]]
            tri_area += 0.5 * np.linalg.norm(np.cross(p[1:-1] - p[0], p[2:] - p[0]).sum(0))
        h = (tri_area / faces_wanted) ** 0.5

        def remesh(h, relax_iterations=10):
            start = time.perf_counter()
            quads = native.quad_remesh(vertices, indices, sizes, positions, edge_length=h,
                                       relax_iterations=relax_iterations)
            return quads, time.perf_counter() - start

        try:
            ours, row["seconds_ours"] = remesh(h)
        except native.Error as error:  # a row saying why, not a lost table
            row["error"] = str(error)
            continue

        obj = new_object(name, vertices, indices, sizes)
        bpy.ops.object.select_all(action='DESELECT')
        obj.select_set(True)
        bpy.context.view_layer.objects.active = obj
        start = time.perf_counter()
        try:
            bpy.ops.object.quadriflow_remesh(mode='FACES', target_faces=len(ours["face_sizes"]))
            row["seconds_quadriflow"] = time.perf_counter() - start
            row["quadriflow"] = mesh_figures(*mesh_arrays(obj), reference)
            # QuadriFlow only aims at its target: our spacing follows its count instead, so
            # both are measured at the same number of quads (regular share and Hausdorff
            # distance both change with it).
            # The count moves in jumps as planes snap to other steps: spacings around the
            # estimate are tried (without relaxation, which keeps the count), the nearest kept.
            target = row["quadriflow"]["faces"]
            estimate = h * (len(ours["face_sizes"]) / target) ** 0.5
            candidates = [estimate * (1.0 + 0.004 * k) for k in range(-25, 26)]
            h = min(candidates, key=lambda x: abs(len(remesh(x, 0)[0]["face_sizes"]) - target))
            ours, row["seconds_ours"] = remesh(h)
        except RuntimeError as error:
            row["quadriflow_error"] = str(error).strip().splitlines()[-1]
        quadriflow_object = obj
        row["ours"] = mesh_figures(ours["vertices"], ours["face_indices"], ours["face_sizes"], reference)
        unrelaxed = remesh(h, relax_iterations=0)[0]
        row["ours_unrelaxed"] = mesh_figures(unrelaxed["vertices"], unrelaxed["face_indices"],
                                             unrelaxed["face_sizes"], reference)

        start = time.perf_counter()
        uv = native.polycube_uv(vertices, indices, sizes, positions)
        row["seconds_uv_ours"] = time.perf_counter() - start
        row["uv_ours"] = dict(native.uv_figures(vertices, indices, sizes, uv["uvs"]), islands_charts=uv["islands"])
        start = time.perf_counter()
        uv = native.polycube_uv(vertices, indices, sizes, positions, relax=True)
        row["seconds_uv_conformal"] = time.perf_counter() - start
        row["uv_conformal"] = native.uv_figures(vertices, indices, sizes, uv["uvs"])
        start = time.perf_counter()
        uv = native.polycube_uv(vertices, indices, sizes, positions, merge=0.01)
        row["seconds_uv_merged"] = time.perf_counter() - start
        row["uv_merged"] = native.uv_figures(vertices, indices, sizes, uv["uvs"])
        obj = new_object(name + " smart", vertices, indices, sizes)
        obj.data.uv_layers.new(name="UVMap")
        bpy.context.view_layer.objects.active = obj
        obj.select_set(True)
        bpy.ops.object.mode_set(mode='EDIT')
        bpy.ops.mesh.select_all(action='SELECT')
        start = time.perf_counter()
        bpy.ops.uv.smart_project()
        row["seconds_uv_smart"] = time.perf_counter() - start
        bpy.ops.object.mode_set(mode='OBJECT')
        row["uv_smart"] = native.uv_figures(vertices, indices, sizes, corner_uvs(obj))
        bpy.data.objects.remove(obj)
        if pictures and name in PICTURED:
            textured = new_object(name + " polycube UV", vertices, indices, sizes)
            layer = textured.data.uv_layers.new(name="Polycube")
            layer.data.foreach_set("uv", np.asarray(
                native.polycube_uv(vertices, indices, sizes, positions)["uvs"], np.float32).ravel())
            shown[name] = (new_object(name + " quads", ours["vertices"], ours["face_indices"], ours["face_sizes"]),
                           quadriflow_object, textured)
        else:
            bpy.data.objects.remove(quadriflow_object)

    (OUT / "results.json").write_text(json.dumps(rows, indent=1))
    if pictures:
        render_pictures(shown, pathlib.Path(pictures))
    print("TABLE Remesh (ours / QuadriFlow at our face count):\nTABLE")
    print("TABLE | model | faces | quads % | regular vertices % (irregular) | Hausdorff / diagonal (unrelaxed) | "
          "manifold, closed | seconds |")
    print("TABLE |---|---|---|---|---|---|---|")
    for row in rows:
        if not row["exact"]:
            print(f"TABLE | {row['model']} | not an exact polycube today | | | | | |")
            continue
        if "error" in row:
            print(f"TABLE | {row['model']} | remesh failed: {row['error']} | | | | | |")
            continue
        o, q = row["ours"], row.get("quadriflow")
        if q is None:
            print(f"TABLE | {row['model']} | {o['faces']} / failed | {100 * o['quads']:.1f} / - | "
                  f"{100 * o['valence4']:.1f} / - | {o['hausdorff']:.5f} / - | {closed(o)} / - | "
                  f"{row['seconds_ours']:.2f} (+{row['seconds_deform']:.2f} deform) / - |")
            continue
        print(f"TABLE | {row['model']} | {o['faces']} / {q['faces']} | {100 * o['quads']:.1f} / {100 * q['quads']:.1f} | "
              f"{100 * o['valence4']:.2f} ({irregular(o)}) / {100 * q['valence4']:.2f} ({irregular(q)}) | "
              f"{o['hausdorff']:.5f} ({row['ours_unrelaxed']['hausdorff']:.5f}) / {q['hausdorff']:.5f} | "
              f"{closed(o)} / {closed(q)} | "
              f"{row['seconds_ours']:.2f} (+{row['seconds_deform']:.2f} deform) / {row['seconds_quadriflow']:.2f} |")
    print("TABLE\nTABLE UV (ours: polycube positions / --relax: conformal in the same islands / --merge 0.01: "
          "conformal, islands merged / Smart UV Project):\nTABLE")
    print("TABLE | model | angle distortion | area distortion | islands | seam length | UV-collapsed area % | seconds |")
    print("TABLE |---|---|---|---|---|---|---|")
    for row in rows:
        if not row["exact"] or "error" in row:
            continue
        figures = [row[k] for k in ("uv_ours", "uv_conformal", "uv_merged", "uv_smart")]

        def three(key, form):
            return " / ".join(format(f[key], form) for f in figures)
        seconds = " / ".join(f"{row[k]:.3f}" for k in ("seconds_uv_ours", "seconds_uv_conformal", "seconds_uv_merged",
                                                         "seconds_uv_smart"))
        collapsed = " / ".join(f"{100 * f['collapsed_area']:.2f}" for f in figures)
        print(f"TABLE | {row['model']} | {three('angle_distortion', '.3f')} | {three('area_distortion', '.3f')} | "
              f"{three('islands', 'd')} | {three('seam_length', '.3g')} | {collapsed} | {seconds} |")

if __name__ == "__main__":
    if "bpy" in sys.modules or "--" in sys.argv:
        inside_blender(sys.argv[sys.argv.index("--") + 1:])
    else:
        outside_blender()
