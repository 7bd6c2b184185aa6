#!/usr/bin/env python3
"""Automatic labels, then the default solver, on the development set of real
models: one Markdown row per model, every figure computed here from the meshes
(input, output, labels), not taken from the solver's own report.

    /usr/bin/python3 tests/benchmark/labels_table.py [--models a,b] [--jobs 1] [--out DIR]

Each model: `polycube label IN` (timed), then `polycube deform IN --labels L`
(timed), writing the polycube and the labels the run ended with. A model is
*exact* when its largest normal deviation from the final labels is below
0.5 degrees, no face is flipped and it has no more folded edges than the
input; *good* when also under 0.5% of the area and 1% of the faces collapsed
and the labeller's labels pass `validate` (*valid*: an exact polycube of
labels that break the polycube conditions is degenerate). Collapsed is
measured twice: per face of the mesh as given (a polygon whose area fell
below 1e-3 of its scaled input area; this decides *good*) and per triangle
of the solver's split of the polygons (stricter on quad meshes: a quad bent
to a triangle's shape, one corner at 180 degrees, keeps its area, but one of
its two triangles has none). On triangle meshes the two agree.
The largest area ratio (a triangle's output area over its scaled input
area) shows fins: a few small triangles stretched far out of their chart,
which otherwise show only as a jump in the area error.
Suzanne (and Suzanne with a level-2 subdivision surface applied) is exported
from Blender once into build/data/.
"""
import argparse
import concurrent.futures
import json
import os
import pathlib
import re
import subprocess
import sys
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
MESHES = ROOT / "build" / "data" / "meshes"
SHARED = ROOT.parent / "shared" / "data"

LIBCGAL = ["elephant", "armadillo", "bunny00", "anchor", "fandisk", "eight", "cactus", "joint",
           "double-torus-example", "bear", "lion", "mushroom", "diplodocus", "ChineseDragon-10kv", "turbine",
           "blade", "mech-holes-shark", "handle", "knot2", "bones"]
MODELS = {name: MESHES / f"{name}.off" for name in LIBCGAL}
MODELS.update({"B0": SHARED / "B0" / "surface.obj", "bone": SHARED / "bone" / "surface.obj",
               "suzanne": ROOT / "build" / "data" / "suzanne.obj",
               "suzanne-subsurf2": ROOT / "build" / "data" / "suzanne-subsurf2.obj"})

SUZANNE_SCRIPT = """
import bpy, sys
def export(path):
    ob = bpy.context.active_object
    mesh = ob.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
    with open(path, "w") as f:
        for v in mesh.vertices: f.write("v %.9g %.9g %.9g\\n" % tuple(v.co))
        for p in mesh.polygons: f.write("f " + " ".join(str(i + 1) for i in p.vertices) + "\\n")
bpy.ops.mesh.primitive_monkey_add()
export(sys.argv[-2])
bpy.ops.object.modifier_add(type='SUBSURF')
bpy.context.active_object.modifiers[-1].levels = 2
export(sys.argv[-1])
"""


def ensure_suzanne():
    a, b = MODELS["suzanne"], MODELS["suzanne-subsurf2"]
    if a.exists() and b.exists():
        return
    a.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run(["blender", "-b", "--factory-startup", "--python-expr", SUZANNE_SCRIPT, "--", str(a), str(b)],
                   check=True, capture_output=True)


def read_mesh(path):
    """Vertices and polygon faces of an OFF, OBJ or ASCII PLY written by polycube."""
    text = pathlib.Path(path).read_text().split("\n")
    path = str(path)
    if path.endswith(".obj"):
        v = [list(map(float, l.split()[1:4])) for l in text if l.startswith("v ")]
        f = [[int(t.split("/")[0]) - 1 for t in l.split()[1:]] for l in text if l.startswith("f ")]
        return np.array(v), f
    tokens = [l.split("#")[0].split() for l in text]
    tokens = [t for t in tokens if t]
    if tokens[0][0].upper().endswith("OFF"):
        head = tokens[0][1:] if len(tokens[0]) > 1 else tokens[1]
        start = 1 if len(tokens[0]) > 1 else 2
        nv, nf = int(head[0]), int(head[1])
        v = np.array([list(map(float, t[:3])) for t in tokens[start:start + nv]])
        f = [list(map(int, t[1:1 + int(t[0])])) for t in tokens[start + nv:start + nv + nf]]
        return v, f
    raise ValueError(f"cannot read {path}")


def read_labels(path):
    return [int(l.split()[0]) for l in pathlib.Path(path).read_text().splitlines() if l.strip() and l[0] != "#"]


def _ear_clip(points):
    """Ear clipping of a counter-clockwise 2-D outline, as native/mesh/triangulate.cpp does it."""
    def cross(a, b):
        return a[0] * b[1] - a[1] * b[0]

    def inside(p, a, b, c):
        return cross(b - a, p - a) >= 0 and cross(c - b, p - b) >= 0 and cross(a - c, p - c) >= 0

    ring, ears = list(range(len(points))), []
    while len(ring) > 3:
        m, clipped = len(ring), False
        for k in range(m):
            i0, i1, i2 = ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]
            a, b, c = points[i0], points[i1], points[i2]
            if cross(b - a, c - b) <= 0:
                continue
            if any(inside(points[q], a, b, c) for q in ring if q not in (i0, i1, i2)):
                continue
            ears.append((i0, i1, i2))
            del ring[k]
            clipped = True
            break
        if not clipped:
            return None
    return ears + [tuple(ring)]


def triangles(vertices, faces):
    """The solver's triangles of the polygons (on the input) and the polygon of each."""
    tris, owner = [], []
    for i, f in enumerate(faces):
        ears = None
        if len(f) > 3:
            p = vertices[f]
            n = sum(np.cross(p[k], p[(k + 1) % len(f)]) for k in range(len(f)))
            if np.linalg.norm(n) > 0:
                n = n / np.linalg.norm(n)
                u = np.cross([1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0], n)
                u /= np.linalg.norm(u)
                ears = _ear_clip([np.array([q @ u, q @ np.cross(n, u)]) for q in p])
        if ears is None:
            ears = [(0, k, k + 1) for k in range(1, len(f) - 1)]
        for e in ears:
            tris.append(tuple(f[j] for j in e))
            owner.append(i)
    return np.array(tris), np.array(owner)


AXES = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)


def figures(v_in, v_out, faces, labels):
    """The quality figures of docs/design.md section 4, from the meshes."""
    tri, owner = triangles(v_in, faces)

    def normals(v):
        c = np.cross(v[tri[:, 1]] - v[tri[:, 0]], v[tri[:, 2]] - v[tri[:, 0]])
        a = 0.5 * np.linalg.norm(c, axis=1)
        with np.errstate(invalid="ignore", divide="ignore"):
            n = c / (2 * a[:, None])
        return n, a

    n_in, a_in = normals(v_in)
    n_out, a_out = normals(v_out)
    s2 = a_out.sum() / a_in.sum()
    collapsed = a_out < 1e-3 * s2 * a_in
    ok = ~collapsed
    axis = AXES[np.asarray(labels)[owner]]
    dot = np.clip((n_out * axis).sum(1), -1, 1)
    deviation = np.degrees(np.arccos(dot))
    nearest = np.degrees(np.arccos(np.clip(np.abs(n_out).max(1), -1, 1)))
    # Edges with exactly two triangles.
    e = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    t = np.tile(np.arange(len(tri)), 3)
    order = np.lexsort((e[:, 1], e[:, 0]))
    e, t = e[order], t[order]
    same = np.all(e[1:] == e[:-1], axis=1)
    first = np.where(same)[0]
    # Keep only edges seen exactly twice.
    counts = np.ones(len(e), dtype=int)
    key = e[:, 0].astype(np.int64) * (len(v_in) + 1) + e[:, 1]
    _, inverse, cnt = np.unique(key, return_inverse=True, return_counts=True)
    two = cnt[inverse[first]] == 2
    ta, tb = t[first[two]], t[first[two] + 1]
    del counts

    def folded(n, valid):
        d = (n[ta] * n[tb]).sum(1)
        return int(np.count_nonzero(valid[ta] & valid[tb] & (d < -0.5)))

    in_valid = a_in > 0
    # Edge error over unique edges.
    uniq = np.unique(key)
    ea, eb = uniq // (len(v_in) + 1), uniq % (len(v_in) + 1)
    l_in = np.linalg.norm(v_in[ea] - v_in[eb], axis=1)
    l_out = np.linalg.norm(v_out[ea] - v_out[eb], axis=1)
    good = l_in > 0
    s = np.sqrt(s2)
    def polygon_areas(v):
        return np.array([0.5 * np.linalg.norm(sum(np.cross(v[f[k]], v[f[(k + 1) % len(f)]]) for k in range(len(f))))
                         for f in faces])

    p_in, p_out = polygon_areas(v_in), polygon_areas(v_out)
    polygon_collapsed = p_out < 1e-3 * (p_out.sum() / p_in.sum()) * p_in
    return {
        "polygon_collapsed_faces_pct": 100.0 * polygon_collapsed.sum() / len(faces),
        "polygon_collapsed_area_pct": 100.0 * p_in[polygon_collapsed].sum() / p_in.sum(),
        "max_deg": float(deviation[ok].max()) if ok.any() else 0.0,
        "mean_deg": float((deviation[ok] * a_in[ok]).sum() / a_in[ok].sum()) if ok.any() else 0.0,
        "nearest_max_deg": float(nearest[ok].max()) if ok.any() else 0.0,
        "flipped": int(np.count_nonzero(ok & (dot < 0))),
        "folded_in": folded(n_in, in_valid),
        "folded_out": folded(n_out, ok),
        "collapsed": int(collapsed.sum()),
        "collapsed_faces_pct": 100.0 * collapsed.sum() / len(tri),
        "collapsed_area_pct": 100.0 * a_in[collapsed].sum() / a_in.sum(),
        "edge_error": float(np.mean(np.abs(l_out[good] / (s * l_in[good]) - 1))),
        "area_error": float(np.mean(np.abs(a_out[in_valid] / (s2 * a_in[in_valid]) - 1))),
        # A fin: a few small triangles stretched far out of their charts, which
        # the other figures show only as a jump in the area error.
        "max_area_ratio": float((a_out[in_valid] / (s2 * a_in[in_valid])).max()) if in_valid.any() else 0.0,
        "triangles": len(tri),
    }


def charts(faces, labels):
    """Connected sets of faces with one label, across shared edges."""
    parent = list(range(len(faces)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    seen = {}
    for i, f in enumerate(faces):
        for k in range(len(f)):
            e = tuple(sorted((f[k], f[(k + 1) % len(f)])))
            j = seen.setdefault(e, i)
            if j != i and labels[i] == labels[j]:
                parent[find(i)] = find(j)
    return len({find(i) for i in range(len(faces))})


def run_model(name, path, program, out, extra):
    out.mkdir(parents=True, exist_ok=True)
    labels_file, final_labels, polycube, report = (out / f"{name}.labels", out / f"{name}.final.labels",
                                                   out / f"{name}.polycube.off", out / f"{name}.json")
    start = time.perf_counter()
    run = subprocess.run([program, "label", str(path), "--output", str(labels_file)] + extra,
                         capture_output=True, text=True)
    if run.returncode != 0:
        return {"model": name, "error": "label: " + run.stderr.strip()}
    label_seconds = time.perf_counter() - start
    violations = re.search(r"(\d+) violations", run.stdout)
    start = time.perf_counter()
    run = subprocess.run([program, "deform", str(path), "--labels", str(labels_file), "--output", str(polycube),
                          "--output-labels", str(final_labels), "--report", str(report)],
                         capture_output=True, text=True)
    deform_seconds = time.perf_counter() - start
    if run.returncode != 0:
        return {"model": name, "error": "deform: " + run.stderr.strip()}
    rep = json.loads(report.read_text())
    v_in, faces = read_mesh(path)
    v_out, _ = read_mesh(polycube)
    given = read_labels(labels_file)
    final = read_labels(final_labels)
    row = {"model": name, "faces": len(faces), "charts": charts(faces, final),
           "relabelled": sum(a != b for a, b in zip(given, final)), "iterations": rep["iterations"],
           "flat_at": rep.get("flat_iteration", 0), "s_label": label_seconds, "s_deform": deform_seconds,
           "peak_mib": rep.get("peak_mib", 0.0)}
    row.update(figures(v_in, v_out, faces, final))
    given_figures = figures(v_in, v_out, faces, given)
    row["max_deg_given"], row["flipped_given"] = given_figures["max_deg"], given_figures["flipped"]
    row["exact"] = bool(row["max_deg"] < 0.5 and row["flipped"] == 0 and row["folded_out"] <= row["folded_in"])
    row["valid"] = bool(violations and violations.group(1) == "0")
    row["good"] = bool(row["exact"] and row["valid"] and row["polygon_collapsed_area_pct"] < 0.5 and
                       row["polygon_collapsed_faces_pct"] < 1.0)
    return row


def model_path(name):
    """A development-set model, another libcgal-demo model by name, or a mesh file."""
    if name in MODELS:
        return MODELS[name]
    return MESHES / f"{name}.off" if (MESHES / f"{name}.off").exists() else pathlib.Path(name)


def run_guarded(name, *args):
    try:
        return run_model(name, *args)
    except Exception as e:  # a row saying why, not a lost table
        return {"model": name, "error": f"{type(e).__name__}: {e}"}


COLUMNS = [("model", "{model}"), ("faces", "{faces}"), ("charts", "{charts}"), ("exact", "{exact}"),
           ("valid", "{valid}"), ("good", "{good}"), ("max°", "{max_deg:.2f}"), ("max° given", "{max_deg_given:.2f}"),
           ("flipped", "{flipped}"), ("flipped given", "{flipped_given}"),
           ("folded in→out", "{folded_in}→{folded_out}"),
           ("collapsed area %", "{polygon_collapsed_area_pct:.2f}"),
           ("collapsed faces %", "{polygon_collapsed_faces_pct:.2f}"),
           ("collapsed triangles: area %", "{collapsed_area_pct:.2f}"), ("triangles %", "{collapsed_faces_pct:.2f}"),
           ("edge err", "{edge_error:.3f}"), ("area err", "{area_error:.3f}"),
           ("max area ratio", "{max_area_ratio:.1f}"), ("relabelled", "{relabelled}"),
           ("iters", "{iterations}"), ("flat at", "{flat_at}"), ("s label", "{s_label:.1f}"),
           ("s deform", "{s_deform:.1f}"), ("MiB", "{peak_mib:.0f}")]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--models", default=",".join(MODELS),
                        help="names from the development set, other libcgal-demo names, or mesh paths")
    parser.add_argument("--program", default=str(ROOT / "build" / "polycube"))
    parser.add_argument("--out", default=str(ROOT / "build" / "labels_table"))
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--json", help="also write the rows here")
    parser.add_argument("label_args", nargs="*", help="passed to `polycube label` (after --)")
    args = parser.parse_args()
    names = args.models.split(",")
    if any(n.startswith("suzanne") for n in names):
        ensure_suzanne()
    print("| " + " | ".join(t for t, _ in COLUMNS) + " |")
    print("|" + "---|" * len(COLUMNS), flush=True)
    rows = []
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        futures = [pool.submit(run_guarded, pathlib.Path(n).stem, model_path(n), args.program, pathlib.Path(args.out),
                               args.label_args) for n in names]
        for future in futures:
            row = future.result()
            rows.append(row)
            if "error" in row:
                print(f"| {row['model']} | failed: {row['error']} |", flush=True)
            else:
                print("| " + " | ".join(f.format(**row) for _, f in COLUMNS) + " |", flush=True)
    done = [r for r in rows if "error" not in r]
    print(f"\nexact {sum(r['exact'] for r in done)}/{len(rows)}, good (also valid labels, < 0.5% area, < 1% faces collapsed) "
          f"{sum(r['good'] for r in done)}/{len(rows)}")
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    sys.exit(main())
