#!/usr/bin/env python3
"""Prints the quality figures and phase timings of `build/polycube deform` on the
real-model corpus, one Markdown row per model and variant.

    /usr/bin/python3 tests/benchmark/figures_table.py [--variants robust,fixed,current] [--iterations 200]
"""
import argparse
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
MESHES = ROOT / "build" / "data" / "meshes"
SHARED = ROOT.parent / "shared" / "data"

# (name, mesh, labels): labels "nearest", "auto" (the automatic labeller) or a
# labels file. The corpus behind docs/design.md section 2.4: models with nearest-axis and automatic
# labels, the published labelings, then other libcgal-demo models.
LIBCGAL = ["fandisk", "elephant", "eight", "larger_sphere", "mesh_with_border", "cactus", "joint", "anchor",
           "double-torus-example"]
CORPUS = [(name, MESHES / f"{name}.off", labels) for name in LIBCGAL for labels in ("nearest", "auto")] + [
    ("B0", SHARED / "B0" / "surface.obj", SHARED / "B0" / "labeling.txt"),
    ("bone", SHARED / "bone" / "surface.obj", SHARED / "bone" / "labeling.txt"),
    ("bone", SHARED / "bone" / "surface.obj", "auto"),
]

COLUMNS = [
    ("model", "{model}"), ("labels", "{labels}"), ("triangles", "{triangles}"), ("variant", "{variant}"),
    ("iterations", "{iterations}"), ("flat at", "{flat_iteration}"), ("converged", "{converged}"),
    ("max deg", "{normal_deviation_max_deg:.3f}"), ("mean deg", "{normal_deviation_mean_deg:.4f}"),
    ("edge err", "{edge_error:.4f}"), ("area err", "{area_error:.4f}"),
    ("flipped", "{flipped_faces}"), ("collapsed", "{collapsed_faces}"),
    ("s total", "{s_total:.3f}"), ("s assemble", "{s_assemble:.3f}"), ("s factorize", "{s_factorize:.3f}"),
    ("s rotations", "{s_rotations:.3f}"), ("s solve", "{s_solve:.3f}"),
]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--variants", default="robust,fixed,current")
    parser.add_argument("--iterations", type=int, default=200)
    parser.add_argument("--models", default=",".join(dict.fromkeys(name for name, _, _ in CORPUS)))
    parser.add_argument("--program", default=str(ROOT / "build" / "polycube"))
    args = parser.parse_args()
    print("| " + " | ".join(title for title, _ in COLUMNS) + " |")
    print("|" + "---|" * len(COLUMNS))
    for name, mesh, labels in CORPUS:
        if name not in args.models.split(","):
            continue
        if not mesh.exists():
            print(f"skipping {name}: {mesh} is missing (run `make data`)", file=sys.stderr)
            continue
        for variant in args.variants.split(","):
            run = subprocess.run([args.program, "deform", str(mesh), "--labels", str(labels), "--variant", variant,
                                  "--iterations", str(args.iterations)], capture_output=True, text=True)
            if run.returncode != 0:
                print(f"| {name} | {variant} | failed: {run.stderr.strip()} |")
                continue
            report = json.loads(run.stdout)
            row = dict(report, model=name, labels=labels if labels in ("nearest", "auto") else "published",
                       **{f"s_{k}": v for k, v in report["seconds"].items()})
            print("| " + " | ".join(fmt.format(**row) for _, fmt in COLUMNS) + " |", flush=True)


if __name__ == "__main__":
    main()
