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

# (name, mesh, labels): labels "nearest" or a labels file.
CORPUS = [
    ("fandisk", MESHES / "fandisk.off", "nearest"),
    ("elephant", MESHES / "elephant.off", "nearest"),
    ("eight", MESHES / "eight.off", "nearest"),
    ("larger_sphere", MESHES / "larger_sphere.off", "nearest"),
    ("mesh_with_border", MESHES / "mesh_with_border.off", "nearest"),
    ("B0", SHARED / "B0" / "surface.obj", SHARED / "B0" / "labeling.txt"),
    ("bone", SHARED / "bone" / "surface.obj", SHARED / "bone" / "labeling.txt"),
]

COLUMNS = [
    ("model", "{model}"), ("labels", "{labels}"), ("triangles", "{triangles}"), ("variant", "{variant}"),
    ("iterations", "{iterations}"), ("converged", "{converged}"),
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
    parser.add_argument("--models", default=",".join(name for name, _, _ in CORPUS))
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
            row = dict(report, model=name, labels="nearest" if labels == "nearest" else "published",
                       **{f"s_{k}": v for k, v in report["seconds"].items()})
            print("| " + " | ".join(fmt.format(**row) for _, fmt in COLUMNS) + " |", flush=True)


if __name__ == "__main__":
    main()
