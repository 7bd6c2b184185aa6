#!/usr/bin/env python3
"""`make bench`: speed and memory of the native solver on real models, with
ratios measured in the same run (docs/design.md section 2.6, "Cost").

For every model it runs, each in its own process (for its peak memory):
- our default variant to the tolerance;
- the paper-literal variant (`current`: refactorise every iteration) to the
  same tolerance, or the same iteration limit;
- the NumPy/SciPy reference (reference_scipy.py) of the same algorithm.

Ratios:
- ratio_floor: our total / (one factorisation + as many back-substitutions as
  we ran iterations), the linear algebra we cannot avoid;
- ratio_paper: our total / the paper-literal total;
- ratio_scipy: our `fixed` / the SciPy reference's `fixed`, the same plain
  algorithm for the same number of iterations (SciPy has no robust variant;
  it runs at most --scipy-iterations and is extrapolated from its setup and
  per-iteration times, said so in the table).

Then the whole process as a user runs it (whole_process_rows): `polycube
deform MESH --labels L --output OUT.obj --report OUT.json` with the default
settings, wall time and peak RSS of the process (median of --whole-runs runs;
one run for the refined models), with the load average, since the machine
may be shared.

Writes build/bench/results.md, results.json and whole_process.json.
"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

MODELS = [  # name, mesh, labels, refinement levels to reach about a million triangles
    ("fandisk", "build/data/meshes/fandisk.off", "nearest", 3),
    ("armadillo", "build/data/meshes/armadillo.off", "nearest", 2),
    ("bunny00", "build/data/meshes/bunny00.off", "nearest", 2),
    ("B0", "../shared/data/B0/surface.obj", "../shared/data/B0/labeling.txt", 3),
]


# A run longer than this is stopped and reported as such: the paper-literal
# variant can fall back to the slow LDLT factorisation on large meshes
# (indefinite Laplacian) and would hold the benchmark for hours.
TIMEOUT_SECONDS = 480


class TimedOut(RuntimeError):
    pass


def native_run(program, mesh, labels, variant, iterations, tolerance):
    """The program's report, which includes its own peak memory (peak_mib)."""
    try:
        run = subprocess.run([program, "deform", mesh, "--labels", labels, "--variant", variant,
                              "--iterations", str(iterations), "--tolerance", str(tolerance)],
                             capture_output=True, text=True, timeout=TIMEOUT_SECONDS)
    except subprocess.TimeoutExpired:
        raise TimedOut(f"{mesh} ({variant}) took more than {TIMEOUT_SECONDS} s") from None
    if run.returncode != 0 or not run.stdout.strip():
        raise RuntimeError(f"{mesh} ({variant}) failed (exit {run.returncode}): {run.stderr.strip()}")
    return json.loads(run.stdout)


def scipy_seconds(mesh, labels, variant, iterations, limit):
    """Times the reference: setup + first iterations, extrapolated to `iterations`."""
    import numpy as np
    import polycube_native as native
    import reference_scipy

    vertices, indices, sizes = native.read_mesh(mesh)
    if not (sizes == 3).all():
        return float("nan"), 0
    label_array = (native.nearest_labels(vertices, indices, sizes) if labels == "nearest"
                   else np.loadtxt(labels, dtype=int, comments="#"))
    triangles = indices.reshape(-1, 3)
    run = max(2, min(iterations, limit))
    seconds = {}
    reference_scipy.deform(vertices, triangles, label_array, run, variant, seconds)
    # The first iteration carries the factorisation (fixed); the others are
    # what every further iteration costs.
    first, rest = seconds["iterations"][0], seconds["iterations"][1:]
    return seconds["setup"] + first + sum(rest) / len(rest) * (iterations - 1), run


def whole_process_rows(program, cases, runs):
    """Wall time and peak RSS of `polycube deform` as a user runs it: reading the
    mesh and labels, solving, measuring, writing the mesh and the report.
    cases: (name, mesh, labels, runs or None for `runs`)."""
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        output, report = os.path.join(folder, "out.obj"), os.path.join(folder, "report.json")
        for name, mesh, labels, case_runs in cases:
            seconds, mib = [], []
            for _ in range(case_runs or runs):
                start = time.perf_counter()
                child = subprocess.Popen([program, "deform", mesh, "--labels", labels, "--output", output,
                                          "--report", report], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
                _, status, usage = os.wait4(child.pid, 0)
                seconds.append(time.perf_counter() - start)
                child.returncode = os.waitstatus_to_exitcode(status)
                error = child.stderr.read().decode(errors="replace").strip()
                child.stderr.close()
                if child.returncode != 0:
                    raise RuntimeError(f"{mesh}: polycube deform failed (exit {child.returncode}): {error}")
                mib.append(usage.ru_maxrss / 1024.0)  # KiB on Linux
            result = json.loads(pathlib.Path(report).read_text())
            rows.append({"model": name, "triangles": result["triangles"], "runs": len(seconds),
                         "wall_seconds_median": statistics.median(seconds),
                         "peak_rss_mib_median": statistics.median(mib),
                         "solver_seconds": result["seconds"]["total"],
                         "flipped_faces": result["flipped_faces"], "converged": result["converged"],
                         "load_average_1min": os.getloadavg()[0]})
            print(f"{name} whole process: {rows[-1]['wall_seconds_median']:.3f} s, "
                  f"{rows[-1]['peak_rss_mib_median']:.1f} MiB", file=sys.stderr)
    return rows


def whole_process_table(rows):
    columns = ["model", "triangles", "runs", "wall_seconds_median", "peak_rss_mib_median", "solver_seconds",
               "flipped_faces", "converged", "load_average_1min"]
    lines = ["Whole process (`polycube deform MESH --labels L --output OUT.obj --report OUT.json`, "
             "median of the runs):", "", "| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(f"{row[k]:.3f}" if isinstance(row[k], float) else str(row[k]) for k in columns) + " |"
              for row in rows]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--iterations", type=int, default=50,
                        help="iteration limit of every run (runs that do not reach the tolerance stop there)")
    parser.add_argument("--tolerance", type=float, default=0.5)
    parser.add_argument("--default-variant", default="robust")
    parser.add_argument("--scipy-iterations", type=int, default=5, help="SciPy iterations actually timed")
    parser.add_argument("--scipy-compare-iterations", type=int, default=50,
                        help="iterations of `fixed` compared with SciPy (extrapolated on the SciPy side)")
    parser.add_argument("--models", default=",".join(m[0] for m in MODELS))
    parser.add_argument("--no-refined", action="store_true", help="skip the ~1M-triangle refined models")
    parser.add_argument("--whole-runs", type=int, default=5,
                        help="runs of the whole process per model (the refined models run once)")
    parser.add_argument("--whole-only", action="store_true", help="only the whole-process rows")
    args = parser.parse_args()

    build = pathlib.Path(args.build).resolve()
    sys.path.insert(0, str(build))
    program = str(build / "polycube")
    out_dir = build / "bench"
    (out_dir / "models").mkdir(parents=True, exist_ok=True)

    cases = []
    for name, mesh, labels, levels in MODELS:
        if name not in args.models.split(","):
            continue
        mesh_path = (ROOT / mesh).resolve()
        labels_arg = labels if labels == "nearest" else str((ROOT / labels).resolve())
        if not mesh_path.exists():
            print(f"skipping {name}: {mesh_path} is missing (run `make data`)", file=sys.stderr)
            continue
        cases.append((name, str(mesh_path), labels_arg))
        if args.no_refined:
            continue
        refined = out_dir / "models" / f"{name}-x{4 ** levels}.ply"
        if not refined.exists():
            command = [program, "refine", str(mesh_path), "--levels", str(levels), "--scheme", "bilinear",
                       "--output", str(refined)]
            if labels != "nearest":
                command += ["--labels", labels_arg]
            subprocess.run(command, check=True, capture_output=True)
        refined_labels = labels if labels == "nearest" else str(refined) + ".labels"
        cases.append((f"{name} x{4 ** levels}", str(refined), refined_labels))

    whole = whole_process_rows(program, [(name, mesh, labels, 1 if " x" in name else None)
                                         for name, mesh, labels in cases], args.whole_runs)
    (out_dir / "whole_process.json").write_text(json.dumps(whole, indent=2) + "\n")
    if args.whole_only:
        (out_dir / "results.md").write_text(whole_process_table(whole) + "\n")
        print(whole_process_table(whole))
        return

    rows = []
    for name, mesh, labels in cases:
        print(f"{name}: ", end="", flush=True, file=sys.stderr)
        ours = native_run(program, mesh, labels, args.default_variant, args.iterations, args.tolerance)
        print(f"default {ours['seconds']['total']:.2f}s, ", end="", flush=True, file=sys.stderr)
        try:
            paper = native_run(program, mesh, labels, "current", args.iterations, args.tolerance)
            print(f"paper {paper['seconds']['total']:.2f}s, ", end="", flush=True, file=sys.stderr)
        except TimedOut:
            # Slower than the timeout: the ratio is at most ours / timeout.
            paper = "timed out"
            print(f"paper timed out (> {TIMEOUT_SECONDS} s), ", end="", flush=True, file=sys.stderr)
        except RuntimeError as error:  # the paper's iteration can break down (armadillo)
            paper = None
            print(f"paper failed ({error}), ", end="", flush=True, file=sys.stderr)
        # SciPy has the plain algorithm only: compare like with like, `fixed`
        # for the same number of iterations on both sides.
        plain = native_run(program, mesh, labels, "fixed", args.scipy_compare_iterations, 0)
        scipy_total, scipy_ran = scipy_seconds(mesh, labels, "fixed", args.scipy_compare_iterations,
                                               args.scipy_iterations)
        print(f"fixed {plain['seconds']['total']:.2f}s vs scipy {scipy_total:.2f}s", file=sys.stderr)
        seconds = ours["seconds"]
        floor = seconds["factorize"] / max(ours["factorizations"], 1) + seconds["solve"]
        for variant, report in ((args.default_variant, ours), ("current (paper)", paper)):
            if report is None or report == "timed out":
                rows.append({"model": name, "variant": variant,
                             "converged": "failed" if report is None else f"timed out (> {TIMEOUT_SECONDS} s)"})
                continue
            row = {
                "model": name, "triangles": report["triangles"], "variant": variant,
                "iterations": report["iterations"], "converged": report["converged"],
                "seconds_total": report["seconds"]["total"],
                **{f"seconds_{k}": v for k, v in report["seconds"].items() if k != "total"},
                "peak_mib": report["peak_mib"], "flipped_faces": report["flipped_faces"],
                "collapsed_faces": report["collapsed_faces"],
                "normal_deviation_max_deg": report["normal_deviation_max_deg"],
                "normal_deviation_mean_deg": report["normal_deviation_mean_deg"],
                "edge_error": report["edge_error"], "area_error": report["area_error"],
                "solver": report["solver"], "factorizations": report["factorizations"],
            }
            if report is ours:
                row.update(ratio_floor=seconds["total"] / floor if floor > 0 else float("nan"),
                           ratio_paper=(f"< {seconds['total'] / TIMEOUT_SECONDS:.3f}" if paper == "timed out"
                                        else seconds["total"] / paper["seconds"]["total"] if paper
                                        else float("nan")),
                           ratio_scipy=plain["seconds"]["total"] / scipy_total,
                           scipy_seconds=scipy_total, scipy_iterations_timed=scipy_ran)
            rows.append(row)

    (out_dir / "results.json").write_text(json.dumps(rows, indent=2) + "\n")
    columns = ["model", "triangles", "variant", "iterations", "converged", "seconds_total", "seconds_factorize",
               "seconds_solve", "peak_mib", "flipped_faces", "collapsed_faces", "normal_deviation_max_deg",
               "edge_error", "area_error", "ratio_floor", "ratio_paper", "ratio_scipy"]

    def cell(row, key):
        value = row.get(key, "")
        return f"{value:.3f}" if isinstance(value, float) else str(value)

    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(cell(row, key) for key in columns) + " |" for row in rows]
    lines.append("")
    lines.append(f"ratio_scipy: our `fixed` / SciPy `fixed`, {args.scipy_compare_iterations} iterations each (SciPy "
                 f"timed for {args.scipy_iterations}, extrapolated). ratio_floor: our total / (one factorisation + "
                 "our back-substitutions). ratio_paper: our total / the paper-literal `current` total.")
    table = "\n".join(lines) + "\n\n" + whole_process_table(whole)
    (out_dir / "results.md").write_text(table + "\n")
    print(table)


if __name__ == "__main__":
    main()
