#!/usr/bin/env python3
"""`make bench`: speed and memory of the native solver on real models, with
ratios measured in the same run (docs/design.md section 2.6, "Cost").

For every model (and, unless --quick, its ~1M-triangle refinement) it runs,
each in its own process (for its peak memory), one row each:
- our default variant (`robust`) to the tolerance, with the cost of each
  stage (set-up; per iteration: fitting, continuous fallback, relaxing flat
  charts, measuring; per call: flattening, untangling) and the reference
  units of the same mesh measured by the same process: one numeric
  factorisation of the input's Laplacian, one back-substitution with it and
  one measurement of every figure;
- on the enlarged models whose labels do not flatten without help
  (CONTINUOUS_MODELS), the default with `--coarse-triangles 0`: the mesh
  deformed at its own resolution, what the coarse route (docs/design.md
  section 2.8) saves;
- the paper-literal variant (`current`: refactorise every iteration) to the
  same tolerance, or the same iteration limit;
- `fixed` for --scipy-compare-iterations against the NumPy/SciPy reference
  (reference_scipy.py) of the same plain algorithm (SciPy runs at most
  --scipy-iterations and is extrapolated from its set-up and per-iteration
  times, said so in the table).

Every run is bounded by --timeout: a run stopped there is a row with that
bound, a run that fails is a row with its message, and the tables are
written after every row, so `make bench` always finishes with a table.

Ratios:
- continuous_units: the default variant's mean seconds per continuous
  iteration, its measurement included / (one back-substitution + one
  measurement);
- ratio_floor: our total / floor, floor = one factorisation of the input's
  Laplacian + our back-substitutions (the report's back_substitutions, each
  timed as one with the input's factorisation), all timed in the same run:
  the linear algebra of a run that factorised once and then only solved
  (docs/design.md section 2.6, "Cost"). Set-up, fitting rotations,
  flattening's extra factorisations, untangling, step control and
  measurement are all above it;
- ratio_paper: our total / the paper-literal total;
- ratio_scipy: our `fixed` / the SciPy reference's `fixed`.

Then the whole process as a user runs it (whole_process_rows): `polycube
deform MESH --labels L --output OUT.obj --report OUT.json` with the default
settings, wall time and peak RSS of the process (median of --whole-runs runs;
one run for the refined models), with the load average, since the machine
may be shared.

Writes build/bench/results.md, results.json and whole_process.json (or into
--output).
"""
import argparse
import json
import math
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
# The enlarged models whose continuous phase must cost a few back-substitutions
# per iteration, and the one that reaches its exact polycube they are held to.
CONTINUOUS_MODELS = ("fandisk x64", "armadillo x16", "bunny00 x16")
EXACT_MODEL = "B0 x64"
OWN_RESOLUTION_VARIANT = "robust --coarse-triangles 0"

# The paper-literal variant can fall back to the slow LDLT factorisation on
# large meshes (indefinite Laplacian) and would hold the benchmark for hours.
TIMEOUT_SECONDS = 480

# The stages of the report (docs/design.md section 2.6), each timed without the others.
STAGES = ("set_up", "fit", "continuous", "relax", "flatten", "untangle", "measure", "polish")


class RunError(RuntimeError):
    """A run that did not give a report: `bound` is set when it timed out."""

    def __init__(self, message, bound=None):
        super().__init__(message)
        self.bound = bound


def native_run(program, mesh, labels, variant, iterations, tolerance, timeout, extra=()):
    """The program's report, which includes its own peak memory (peak_mib)."""
    command = [program, "deform", mesh, "--labels", labels, "--variant", variant,
               "--iterations", str(iterations), "--tolerance", str(tolerance), *extra]
    try:
        run = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise RunError(f"stopped after {timeout:g} s", bound=timeout) from None
    if run.returncode != 0 or not run.stdout.strip():
        message = (run.stderr.strip().splitlines() or ["no output"])[-1]
        raise RunError(f"exit {run.returncode}: {message}")
    try:
        return json.loads(run.stdout)
    except json.JSONDecodeError as error:
        raise RunError(f"unreadable report: {error}") from None


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


def whole_process_rows(program, cases, runs, timeout, add_row):
    """Wall time and peak RSS of `polycube deform` as a user runs it: reading the
    mesh and labels, solving, measuring, writing the mesh and the report.
    cases: (name, mesh, labels, runs or None for `runs`). Every run is bounded by
    `timeout`; a case that times out or fails is a row with its message."""
    with tempfile.TemporaryDirectory() as folder:
        output, report = os.path.join(folder, "out.obj"), os.path.join(folder, "report.json")
        for name, mesh, labels, case_runs in cases:
            try:
                row = whole_process_row(program, name, mesh, labels, case_runs or runs, timeout, output, report)
                print(f"{name} whole process: {row['wall_seconds_median']:.3f} s, "
                      f"{row['peak_rss_mib_median']:.1f} MiB", file=sys.stderr)
            except Exception as error:  # noqa: BLE001 - one model's failure is its row, not the end
                bound = getattr(error, "bound", None)
                row = {"model": name, "converged": "timed out" if bound else "failed", "message": str(error)}
                if bound:
                    row["wall_seconds_median"] = f"> {bound:g}"
                print(f"{name} whole process: {error}", file=sys.stderr)
            add_row(row)


def whole_process_row(program, name, mesh, labels, runs, timeout, output, report):
    seconds, mib = [], []
    for _ in range(runs):
        start = time.perf_counter()
        child = subprocess.Popen([program, "deform", mesh, "--labels", labels, "--output", output,
                                  "--report", report], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        try:
            # wait4 for the child's own peak RSS; a poll loop so the run stays bounded.
            while True:
                pid, status, usage = os.wait4(child.pid, os.WNOHANG)
                if pid:
                    break
                if time.perf_counter() - start > timeout:
                    child.kill()
                    os.wait4(child.pid, 0)
                    raise RunError(f"stopped after {timeout:g} s", bound=timeout)
                time.sleep(0.02)
        finally:
            error = child.stderr.read().decode(errors="replace").strip()
            child.stderr.close()
        seconds.append(time.perf_counter() - start)
        child.returncode = os.waitstatus_to_exitcode(status)
        if child.returncode != 0:
            message = (error.splitlines() or ["no output"])[-1]
            raise RunError(f"exit {child.returncode}: {message}")
        mib.append(usage.ru_maxrss / 1024.0)  # KiB on Linux
    result = json.loads(pathlib.Path(report).read_text())
    return {"model": name, "triangles": result["triangles"], "runs": len(seconds),
            "wall_seconds_median": statistics.median(seconds),
            "peak_rss_mib_median": statistics.median(mib),
            "solver_seconds": result["seconds"]["total"],
            "flipped_faces": result["flipped_faces"], "converged": result["converged"],
            "load_average_1min": os.getloadavg()[0]}


WHOLE_COLUMNS = ["model", "triangles", "runs", "wall_seconds_median", "peak_rss_mib_median", "solver_seconds",
                 "flipped_faces", "converged", "load_average_1min", "message"]


def per(seconds, count):
    return seconds / count if count else float("nan")


def report_row(name, variant, report):
    """The figures and costs of one run's report."""
    seconds = report["seconds"]
    row = {
        "model": name, "triangles": report["triangles"], "variant": variant,
        "iterations": report["iterations"], "kept_iteration": report.get("kept_iteration", report["iterations"]),
        "converged": report["converged"],
        "seconds_total": seconds["total"],
        **{f"seconds_{k}": v for k, v in seconds.items() if k != "total"},
        "peak_mib": report["peak_mib"], "flipped_faces": report["flipped_faces"],
        "folded_edges": report["folded_edges"], "collapsed_faces": report["collapsed_faces"],
        "collapsed_area": report["collapsed_area"],
        "normal_deviation_max_deg": report["normal_deviation_max_deg"],
        "normal_deviation_mean_deg": report["normal_deviation_mean_deg"],
        "edge_error": report["edge_error"], "area_error": report["area_error"],
        "solver": report["solver"], "factorizations": report["factorizations"],
        "flat_iteration": report.get("flat_iteration", 0),
    }
    stages = report.get("stages", {})
    for stage in STAGES:
        cost = stages.get(stage, {"count": 0, "seconds": 0.0})
        row[f"{stage}_count"] = cost["count"]
        row[f"{stage}_seconds"] = cost["seconds"]
        row[f"{stage}_per"] = per(cost["seconds"], cost["count"])
    row["current_steps"] = stages.get("current_steps", 0)
    row["back_substitutions"] = report.get("back_substitutions", 0)
    # Per attempt at flattening: its seconds, of them untangling, and the rounds of each.
    row["flatten_attempts"] = [
        {key: attempt.get(key) for key in ("iteration", "kept", "rounds", "factorizations", "untangle_rounds",
                                           "seconds", "untangle_seconds")}
        for attempt in report.get("flatten_attempts", [])]
    reference = report.get("reference_seconds")
    if reference:
        row["reference_factorize"] = reference.get("factorize", float("nan"))
        row["reference_solve"], row["reference_measure"] = reference["solve"], reference["measure"]
        unit = reference["solve"] + reference["measure"]
        with_measure = row["continuous_per"] + row["measure_per"]
        row["continuous_units"] = with_measure / unit if unit > 0 else float("nan")
        floor = row["reference_factorize"] + row["back_substitutions"] * reference["solve"]
        row["floor_seconds"] = floor
        row["ratio_floor"] = seconds["total"] / floor if floor > 0 else float("nan")
    return row


def failed_row(name, variant, error):
    row = {"model": name, "variant": variant, "converged": "timed out" if error.bound else "failed",
           "message": str(error)}
    if error.bound:
        row["seconds_total"] = f"> {error.bound:g}"
        row["bound_seconds"] = error.bound
    return row


def own_resolution_text(by_key, model, exact_seconds):
    """The run of `model` at its own resolution beside the default's line, against the exact model."""
    own = by_key.get((model, OWN_RESOLUTION_VARIANT))
    if not own:
        return ""
    if not isinstance(own.get("seconds_total"), float):
        return f"; at its own resolution {own.get('converged')} ({own.get('message', '')})"
    text = f"; at its own resolution {own['seconds_total']:.1f} s"
    if exact_seconds:
        text += f" = {own['seconds_total'] / exact_seconds:.2f} x {EXACT_MODEL}"
    return text + f", {100 * own.get('collapsed_area', float('nan')):.3f}% collapsed"


def checks(rows, iterations):
    """The targets of the continuous fallback, as measured in this run."""
    by_key = {(row["model"], row["variant"]): row for row in rows}
    lines = []
    exact = by_key.get((EXACT_MODEL, "robust"))
    exact_seconds = exact.get("seconds_total") if exact and exact.get("converged") is True else None
    for model in CONTINUOUS_MODELS:
        row = by_key.get((model, "robust"))
        if row is None:
            continue
        if not isinstance(row.get("seconds_total"), float):
            text = f"- {model}: {row.get('converged')} ({row.get('message', '')})"
            bound = row.get("bound_seconds")
            if bound and exact_seconds:
                # A bound still decides the target when it is past twice the exact run.
                verdict = "fails" if bound > 2 * exact_seconds else "undecided: the bound is within the target"
                text += (f"; {row.get('variant')} > {bound:g} s = > {bound / exact_seconds:.2f} x {EXACT_MODEL} "
                         f"exact ({exact_seconds:.1f} s) [target <= 2]: {verdict}")
            lines.append(text)
            continue
        attempts = row.get("flatten_count", 0)
        flattening = (f"; flattening {attempts} attempt{'s' if attempts != 1 else ''} at "
                      f"{row['flatten_per']:.1f} s each" if attempts else "")
        untangled = [a for a in row.get("flatten_attempts", []) if a.get("untangle_rounds")]
        if untangled:
            flattening += " (untangling " + ", ".join(
                f"{a['untangle_rounds']} rounds {a['untangle_seconds']:.1f} s" for a in untangled) + ")"
        # Held to twice the exact model's time whether it has continuous iterations or not.
        against_exact = (f"; {row['iterations']} iterations {row['seconds_total']:.1f} s = "
                         f"{row['seconds_total'] / exact_seconds:.2f} x {EXACT_MODEL} exact ({exact_seconds:.1f} s) "
                         "[target <= 2]") if exact_seconds else ""
        if not row.get("continuous_count"):
            # Flat before any continuous iteration: no continuous phase to hold to its target.
            lines.append(f"- {model}: no continuous iteration ({row['iterations']} iterations, "
                         f"{row['seconds_total']:.1f} s{flattening})" + against_exact +
                         own_resolution_text(by_key, model, exact_seconds))
            continue
        units = row.get("continuous_units", float("nan"))
        text = (f"- {model}: continuous iteration {row['continuous_per'] + row['measure_per']:.3f} s (measurement "
                f"included) = {units:.2f} x (back-substitution "
                f"{row.get('reference_solve', float('nan')):.3f} s + measurement "
                f"{row.get('reference_measure', float('nan')):.3f} s) [target <= 3]{flattening}")
        lines.append(text + against_exact + own_resolution_text(by_key, model, exact_seconds))
    if exact and isinstance(exact.get("ratio_floor"), float):
        stages = ", ".join(f"{stage} {exact[f'{stage}_seconds']:.1f} s" for stage in STAGES if exact[f"{stage}_count"])
        lines.append(f"- {EXACT_MODEL}: {exact['seconds_total']:.1f} s = {exact['ratio_floor']:.2f} x floor "
                     f"({exact['floor_seconds']:.1f} s: factorisation {exact['reference_factorize']:.2f} s + "
                     f"{exact['back_substitutions']} x back-substitution {exact['reference_solve']:.3f} s) "
                     f"[target <= 2]; stages: {stages}")
    peaks = [row["peak_mib"] for row in rows if isinstance(row.get("peak_mib"), float)]
    if peaks:
        lines.append(f"- largest peak memory: {max(peaks):.0f} MiB [target < 4096]")
    return lines


COLUMNS = ["model", "triangles", "variant", "iterations", "kept_iteration", "converged", "seconds_total", "peak_mib",
           "flipped_faces", "folded_edges", "collapsed_faces", "collapsed_area", "normal_deviation_max_deg",
           "edge_error", "area_error", "set_up_seconds", "fit_per", "continuous_per", "current_steps", "relax_per",
           "flatten_count", "flatten_per", "untangle_count", "untangle_per", "measure_per", "factorizations",
           "back_substitutions", "reference_factorize", "reference_solve", "reference_measure", "floor_seconds",
           "continuous_units", "ratio_floor", "ratio_paper", "ratio_scipy", "message"]


def table(columns, rows):
    def cell(row, key):
        value = row.get(key, "")
        if isinstance(value, float):
            return "" if math.isnan(value) else f"{value:.3f}"
        return str(value).replace("|", "/")

    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    return lines + ["| " + " | ".join(cell(row, key) for key in columns) + " |" for row in rows]


def write_results(out_dir, rows, whole, args):
    """The tables, rewritten after every row: a run stopped midway leaves what it measured."""
    (out_dir / "results.json").write_text(json.dumps(rows, indent=2) + "\n")
    (out_dir / "whole_process.json").write_text(json.dumps(whole, indent=2) + "\n")
    lines = []
    if not args.whole_only:
        lines += table(COLUMNS, rows) + [
        "",
        "kept_iteration: the iteration whose shape the run returned (0: the input, no later shape folded as "
        "little). The stages of `robust`, each without the others: set_up_seconds before the first iteration "
        "(analysis, assembly, the input's factorisation); seconds per iteration of fitting, the continuous "
        "fallback, relaxing flat charts and measuring (measure_per); per call of flattening (a few solves and "
        "factorisations each) and untangling (a flat shape's collapsed triangles opened). current_steps: the "
        "continuous steps that needed the current mesh's Laplacian. reference_factorize / reference_solve / "
        "reference_measure: one numeric factorisation of the input's Laplacian / one back-substitution with it / "
        "one measurement of every figure, same mesh, same process; continuous_units = (continuous_per + "
        "measure_per) / (reference_solve + reference_measure). floor_seconds = reference_factorize + "
        "back_substitutions x reference_solve; ratio_floor = seconds_total / floor_seconds. ratio_scipy: our "
        f"`fixed` / SciPy `fixed`, {args.scipy_compare_iterations} iterations each (SciPy timed for "
        f"{args.scipy_iterations}, extrapolated). ratio_paper: our total / the "
        f"paper-literal `current` total. Runs stopped after {args.timeout:g} s are bounds.",
        "",
        *checks(rows, args.iterations),
        "",
    ]
    lines += ["Whole process (`polycube deform MESH --labels L --output OUT.obj --report OUT.json`, "
              f"median of the runs; runs stopped after {args.timeout:g} s are bounds):", ""]
    lines += table(WHOLE_COLUMNS, whole)
    (out_dir / "results.md").write_text("\n".join(lines) + "\n")
    return "\n".join(lines)


def prepare_cases(args, program, models_dir):
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
        if args.quick:
            continue
        refined = models_dir / f"{name}-x{4 ** levels}.ply"
        if not refined.exists():
            command = [program, "refine", str(mesh_path), "--levels", str(levels), "--scheme", "bilinear",
                       "--output", str(refined)]
            if labels != "nearest":
                command += ["--labels", labels_arg]
            run = subprocess.run(command, capture_output=True, text=True)
            if run.returncode != 0:
                cases.append((f"{name} x{4 ** levels}", None, f"refining failed: {run.stderr.strip()}"))
                continue
        refined_labels = labels if labels == "nearest" else str(refined) + ".labels"
        cases.append((f"{name} x{4 ** levels}", str(refined), refined_labels))
    return cases


def bench_case(program, name, mesh, labels, args, add_row):
    """The rows of one model: default, paper-literal, fixed against SciPy."""
    def run(variant, iterations, tolerance, extra=()):
        return native_run(program, mesh, labels, variant, iterations, tolerance, args.timeout, extra)

    def say(text):
        print(text, end="", flush=True, file=sys.stderr)

    say(f"{name}: ")
    ours = None
    try:
        report = run(args.default_variant, args.iterations, args.tolerance, ["--time-references"])
        say(f"default {report['seconds']['total']:.2f}s, ")
        ours = report_row(name, args.default_variant, report)
        add_row(ours)
    except RunError as error:
        add_row(failed_row(name, args.default_variant, error))
        say(f"default {error}, ")
    if "own" in args.variants and name in CONTINUOUS_MODELS:
        try:
            own = run(args.default_variant, args.iterations, args.tolerance, ["--coarse-triangles", "0"])
            say(f"at its own resolution {own['seconds']['total']:.2f}s, ")
            add_row(report_row(name, OWN_RESOLUTION_VARIANT, own))
        except RunError as error:
            add_row(failed_row(name, OWN_RESOLUTION_VARIANT, error))
            say(f"at its own resolution {error}, ")
    if "current" in args.variants:
        try:
            paper = run("current", args.iterations, args.tolerance)
            say(f"paper {paper['seconds']['total']:.2f}s, ")
            if ours:
                ours["ratio_paper"] = ours["seconds_total"] / paper["seconds"]["total"]
            add_row(report_row(name, "current (paper)", paper))
        except RunError as error:  # the paper's iteration can break down (armadillo)
            if ours and error.bound:
                ours["ratio_paper"] = f"< {ours['seconds_total'] / error.bound:.3f}"
            add_row(failed_row(name, "current (paper)", error))
            say(f"paper {error}, ")
    if "fixed" in args.variants:
        # SciPy has the plain algorithm only: compare like with like, `fixed`
        # for the same number of iterations on both sides.
        try:
            plain = run("fixed", args.scipy_compare_iterations, 0)
            row = report_row(name, "fixed", plain)
            try:
                scipy_total, scipy_ran = scipy_seconds(mesh, labels, "fixed", args.scipy_compare_iterations,
                                                       args.scipy_iterations)
                row.update(ratio_scipy=plain["seconds"]["total"] / scipy_total, scipy_seconds=scipy_total,
                           scipy_iterations_timed=scipy_ran)
                say(f"fixed {plain['seconds']['total']:.2f}s vs scipy {scipy_total:.2f}s")
            except Exception as error:  # noqa: BLE001 - the reference's failure is a row's message, not the end
                row["message"] = f"scipy reference failed: {error}"
                say(f"fixed {plain['seconds']['total']:.2f}s, scipy failed ({error})")
            add_row(row)
        except RunError as error:
            add_row(failed_row(name, "fixed", error))
            say(f"fixed {error}")
    say("\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--iterations", type=int, default=50,
                        help="iteration limit of every run (runs that do not reach the tolerance stop there)")
    parser.add_argument("--tolerance", type=float, default=0.5)
    parser.add_argument("--timeout", type=float, default=TIMEOUT_SECONDS, help="seconds before a run is a bound")
    parser.add_argument("--default-variant", default="robust")
    parser.add_argument("--variants", default="own,current,fixed",
                        help="other runs besides the default (own: --coarse-triangles 0 on CONTINUOUS_MODELS, "
                             "current: the paper, fixed: against SciPy)")
    parser.add_argument("--scipy-iterations", type=int, default=5, help="SciPy iterations actually timed")
    parser.add_argument("--scipy-compare-iterations", type=int, default=50,
                        help="iterations of `fixed` compared with SciPy (extrapolated on the SciPy side)")
    parser.add_argument("--models", default=",".join(m[0] for m in MODELS))
    parser.add_argument("--output", help="where results.md and results.json go (default: BUILD/bench)")
    parser.add_argument("--quick", "--no-refined", action="store_true",
                        help="the models at their own size only (no ~1M-triangle refinements)")
    parser.add_argument("--whole-runs", type=int, default=5,
                        help="runs of the whole process per model (the refined models run once)")
    parser.add_argument("--whole-only", action="store_true", help="only the whole-process rows")
    args = parser.parse_args()
    args.variants = [v for v in args.variants.split(",") if v]

    build = pathlib.Path(args.build).resolve()
    sys.path.insert(0, str(build))
    program = str(build / "polycube")
    out_dir = pathlib.Path(args.output) if args.output else build / "bench"
    out_dir.mkdir(parents=True, exist_ok=True)
    models_dir = build / "bench" / "models"  # the refined models, made once
    models_dir.mkdir(parents=True, exist_ok=True)

    rows, whole = [], []

    def add_row(row):
        rows.append(row)
        write_results(out_dir, rows, whole, args)

    def add_whole_row(row):
        whole.append(row)
        write_results(out_dir, rows, whole, args)

    write_results(out_dir, rows, whole, args)
    cases = prepare_cases(args, program, models_dir)
    whole_process_rows(program, [(name, mesh, labels, 1 if " x" in name else None)
                                 for name, mesh, labels in cases if mesh is not None],
                       args.whole_runs, args.timeout, add_whole_row)
    for name, mesh, labels in cases:
        if args.whole_only:
            break
        if mesh is None:
            add_row({"model": name, "variant": args.default_variant, "converged": "failed", "message": labels})
            continue
        try:
            bench_case(program, name, mesh, labels, args, add_row)
        except Exception as error:  # noqa: BLE001 - one model's surprise must not cost the others' rows
            add_row({"model": name, "variant": "?", "converged": "failed", "message": repr(error)})
    print(write_results(out_dir, rows, whole, args))


if __name__ == "__main__":
    main()
