"""`make bench`'s check lines (tests/benchmark/bench.py): a run stopped at the
bound still says where it stands against the exact model's time."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "benchmark"))

import bench  # noqa: E402


def exact_row(seconds):
    row = {"model": bench.EXACT_MODEL, "variant": "robust", "converged": True, "seconds_total": seconds}
    return row


def stopped_row(model, bound):
    return bench.failed_row(model, "robust", bench.RunError(f"stopped after {bound:g} s", bound=bound))


def test_a_bound_past_twice_the_exact_run_fails():
    lines = bench.checks([stopped_row("fandisk x64", 480.0), exact_row(200.0)], 50)
    line = next(line for line in lines if line.startswith("- fandisk x64"))
    assert "> 480 s = > 2.40 x B0 x64 exact (200.0 s)" in line
    assert line.endswith(": fails")


def test_a_bound_within_twice_the_exact_run_is_undecided():
    lines = bench.checks([stopped_row("armadillo x16", 480.0), exact_row(300.0)], 50)
    line = next(line for line in lines if line.startswith("- armadillo x16"))
    assert "> 1.60 x" in line and "undecided" in line


def test_without_the_exact_run_a_bound_is_only_stated():
    lines = bench.checks([stopped_row("bunny00 x16", 480.0)], 50)
    assert lines == ["- bunny00 x16: timed out (stopped after 480 s)"]


def test_the_run_at_its_own_resolution_stands_beside_the_default():
    # fandisk x64 flattens before any continuous iteration; its run at its
    # own resolution is stated on the same line against the exact model.
    default = {"model": "fandisk x64", "variant": "robust", "converged": True, "seconds_total": 144.0,
               "iterations": 13, "continuous_count": 0, "flatten_count": 3, "flatten_per": 40.0}
    own = {"model": "fandisk x64", "variant": bench.OWN_RESOLUTION_VARIANT, "converged": True, "seconds_total": 74.0,
           "collapsed_area": 0.00108}
    lines = bench.checks([default, own, exact_row(20.0)], 50)
    line = next(line for line in lines if line.startswith("- fandisk x64"))
    assert line.endswith("; at its own resolution 74.0 s = 3.70 x B0 x64, 0.108% collapsed"), line
    # Without a continuous iteration it is still held to twice the exact model's time.
    assert "; 13 iterations 144.0 s = 7.20 x B0 x64 exact (20.0 s) [target <= 2]" in line, line


def test_a_run_at_its_own_resolution_that_timed_out_is_stated_as_such():
    default = {"model": "bunny00 x16", "variant": "robust", "converged": True, "seconds_total": 70.0,
               "iterations": 25, "continuous_count": 0, "flatten_count": 4, "flatten_per": 4.0}
    own = stopped_row("bunny00 x16", 480.0)
    own["variant"] = bench.OWN_RESOLUTION_VARIANT
    lines = bench.checks([default, own, exact_row(20.0)], 50)
    line = next(line for line in lines if line.startswith("- bunny00 x16"))
    assert line.endswith("; at its own resolution timed out (stopped after 480 s)"), line
