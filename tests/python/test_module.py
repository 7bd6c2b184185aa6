"""The Python module: numpy in and out, keyword options, the callback, errors."""
import threading
import time

import numpy as np
import pytest

from conftest import uv_sphere

REPORT_KEYS = {
    "vertices", "faces", "triangles", "iterations", "converged", "normal_deviation_max_deg",
    "normal_deviation_mean_deg", "edge_error", "area_error", "flipped_faces", "collapsed_faces",
    "variant", "seconds",
}


def test_sphere_becomes_a_cube(native, sphere):
    vertices, indices, sizes = sphere
    labels = native.nearest_labels(vertices, indices, sizes)
    result = native.deform(vertices, indices, sizes, labels, iterations=200, tolerance=0.5)
    report = result["report"]
    assert REPORT_KEYS <= report.keys()
    assert set(report["seconds"]) >= {"total", "assemble", "factorize", "rotations", "solve"}
    assert report["converged"] and report["normal_deviation_max_deg"] < 0.5
    assert report["flipped_faces"] == 0
    assert report["vertices"] == len(vertices) and report["faces"] == len(sizes)
    positions = result["positions"]
    assert positions.shape == vertices.shape and positions.dtype == np.float64
    # Six flat charts: the corners of all faces labelled +-axis share that coordinate.
    extent = np.ptp(positions, axis=0)
    corners_label = np.repeat(labels, sizes)
    for label in range(6):
        coordinate = positions[indices[corners_label == label], label // 2]
        assert np.ptp(coordinate) < 1e-2 * extent[label // 2], native.LABEL_NAMES[label]
    # The module's figures agree with the report.
    figures = native.figures(vertices, positions, indices, sizes, labels)
    assert figures["normal_deviation_max_deg"] == pytest.approx(report["normal_deviation_max_deg"])
    assert figures["edge_error"] == pytest.approx(report["edge_error"])
    assert figures["max_area_ratio"] == pytest.approx(report["max_area_ratio"])
    assert 1.0 <= figures["max_area_ratio"] < 3.0  # a sphere's cube: no fin


def test_input_arrays_are_not_changed_and_any_dtype_is_accepted(native, sphere):
    vertices, indices, sizes = sphere
    before = vertices.copy()
    result = native.deform(vertices.astype(np.float32), indices.astype(np.int64), sizes.tolist(),
                           np.full(len(sizes), -1, dtype=np.int8), iterations=3)
    assert np.array_equal(vertices, before)
    assert result["report"]["unlabelled_faces"] == len(sizes)
    assert np.array_equal(result["labels"], native.nearest_labels(vertices, indices, sizes))


def test_variants_and_iteration_limit(native, sphere):
    vertices, indices, sizes = sphere
    labels = native.nearest_labels(vertices, indices, sizes)
    for variant in ("robust", "fixed", "current"):
        report = native.deform(vertices, indices, sizes, labels, iterations=4, tolerance=0,
                               variant=variant)["report"]
        assert report["variant"] == variant and report["iterations"] == 4
        assert not report["converged"]


def test_callback_sees_each_iteration_and_can_stop(native, sphere):
    vertices, indices, sizes = sphere
    labels = native.nearest_labels(vertices, indices, sizes)
    seen = []

    def callback(iteration, positions, figures):
        seen.append((iteration, positions.copy(), figures))
        return iteration < 4

    result = native.deform(vertices, indices, sizes, labels, iterations=50, tolerance=0, callback=callback)
    assert [s[0] for s in seen] == [1, 2, 3, 4]
    assert result["report"]["stopped"] and result["report"]["iterations"] == 4
    assert np.array_equal(seen[-1][1], result["positions"])
    for iteration, positions, figures in seen:
        assert figures["iteration"] == iteration
        expected = native.figures(vertices, positions, indices, sizes, labels)
        assert figures["normal_deviation_max_deg"] == pytest.approx(expected["normal_deviation_max_deg"])
        assert figures["flipped_faces"] == expected["flipped_faces"]


def test_stop_ends_the_further_runs_and_keeps_the_first(native, real_mesh):
    # The eight's automatic labels collapse faces in the first run; the runs
    # with them relabelled (stage 8) are silent, so only `stop` can end them.
    # A stop once the first run has ended (as Esc would be) ends them before
    # they start; a stop from the start ends the first run after its first
    # iteration.
    vertices, indices, sizes = real_mesh("eight")
    labels = native.auto_labels(vertices, indices, sizes)
    once = native.deform(vertices, indices, sizes, labels, relabel_collapsed=False, polish=False)["report"]
    assert once["converged"] and once["collapsed_faces"] > 0
    seen = [0]

    def watch(iteration, positions, figures):
        seen[0] = iteration

    stopped = native.deform(vertices, indices, sizes, labels, callback=watch,
                            stop=lambda: seen[0] >= once["iterations"])
    assert stopped["report"]["stopped"] and stopped["report"]["second_run_iterations"] == 0
    assert stopped["report"]["collapsed_faces"] == once["collapsed_faces"]
    at_once = native.deform(vertices, indices, sizes, labels, stop=lambda: True)["report"]
    assert at_once["stopped"] and at_once["iterations"] == 1
    further = native.deform(vertices, indices, sizes, labels, stop=lambda: False)["report"]
    assert further["second_run_iterations"] > 0 and further["collapsed_area"] < 0.5 * once["collapsed_area"]


def test_last_resort_makes_the_anchor_exact_and_can_be_turned_off(native, real_mesh):
    # The anchor's automatic labels flatten only above the first run's
    # collapse bound: the first run ends far from a polycube, stage 9 makes
    # it exact with a few percent of the area collapsed.
    vertices, indices, sizes = real_mesh("anchor")
    labels = native.auto_labels(vertices, indices, sizes)
    first = native.deform(vertices, indices, sizes, labels, last_resort=False)["report"]
    assert not first["converged"] and not first["last_resort"]
    assert first["folded_edges"] <= first["input_folded_edges"]
    rescued = native.deform(vertices, indices, sizes, labels)["report"]
    assert rescued["converged"] and rescued["last_resort"]
    assert rescued["normal_deviation_max_deg"] < 0.5 and rescued["flipped_faces"] == 0
    assert rescued["collapsed_area"] < 0.05


def test_polish_lowers_both_errors_and_can_be_turned_off(native, real_mesh):
    # fandisk with its automatic labels (docs/design.md section 2.6, stage 10):
    # edge 0.1075 -> 0.1057, area 0.156 -> 0.132; the polycube stays exact.
    vertices, indices, sizes = real_mesh("fandisk")
    labels = native.auto_labels(vertices, indices, sizes)
    seen = []
    plain = native.deform(vertices, indices, sizes, labels, polish=False)["report"]
    polished = native.deform(vertices, indices, sizes, labels, callback=lambda i, p, f: seen.append(i) or True)
    report = polished["report"]
    assert plain["polish_steps"] == 0 and report["polish_steps"] > 0
    assert report["iterations"] == plain["iterations"] + 1 == len(seen)
    assert report["converged"] and report["normal_deviation_max_deg"] < 1e-6 and report["flipped_faces"] == 0
    assert report["collapsed_faces"] <= plain["collapsed_faces"]
    assert report["edge_error"] < plain["edge_error"] and report["area_error"] < 0.9 * plain["area_error"]
    assert report["stages"]["polish"]["count"] == 1
    figures = native.figures(vertices, polished["positions"], indices, sizes, polished["labels"])
    assert figures["area_error"] == pytest.approx(report["area_error"])


def test_callback_exception_propagates(native, sphere):
    vertices, indices, sizes = sphere

    def callback(iteration, positions, figures):
        raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        native.deform(vertices, indices, sizes, np.zeros(len(sizes), int), iterations=5, callback=callback)


def test_gil_is_released_while_solving(native):
    vertices, indices, sizes = uv_sphere(256, 128)
    labels = native.nearest_labels(vertices, indices, sizes)
    done = threading.Event()

    def solve():
        native.deform(vertices, indices, sizes, labels, iterations=15, tolerance=0)
        done.set()

    worker = threading.Thread(target=solve)
    start = time.perf_counter()
    worker.start()
    ticks = 0
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    elapsed = time.perf_counter() - start
    # Holding the GIL would starve this loop to a tick or two for the whole
    # solve; a loaded machine only makes each tick longer.
    assert elapsed > 0.1, "the solve was too short to tell"
    assert ticks >= 20


@pytest.mark.parametrize("mutate, words", [
    (lambda v, i, s, l: (v[:, :2], i, s, l), r"\(n, 3\)"),
    (lambda v, i, s, l: (np.zeros((0, 3)), i[:0], s[:0], l[:0]), "empty"),
    (lambda v, i, s, l: (v, i[:0], s[:0], l[:0]), "no faces"),
    (lambda v, i, s, l: (np.where(np.arange(len(v))[:, None] == 3, np.nan, v), i, s, l), "non-finite"),
    (lambda v, i, s, l: (v, np.where(np.arange(len(i)) == 7, 10**6, i), s, l),
     r"face_indices\[7\] is 1000000, outside the vertex indices 0\.\.481"),
    (lambda v, i, s, l: (v, i, s, np.where(np.arange(len(l)) == 2, 6, l)), r"outside -1\.\.5"),
    (lambda v, i, s, l: (v, i, s, l[:-1]), "labels for"),
    (lambda v, i, s, l: (v, i[:-1], s, l), "face_sizes add up"),
    (lambda v, i, s, l: (v, i, np.where(np.arange(len(s)) == 0, 2, s), l), "at least 3"),
])
def test_bad_input_raises_value_error(native, sphere, mutate, words):
    vertices, indices, sizes = sphere
    labels = native.nearest_labels(vertices, indices, sizes)
    with pytest.raises(ValueError, match=words):
        native.deform(*mutate(vertices, indices, sizes, labels), iterations=2)


def test_bad_options_raise_value_error(native, sphere):
    vertices, indices, sizes = sphere
    labels = native.nearest_labels(vertices, indices, sizes)
    with pytest.raises(ValueError, match="variant"):
        native.deform(vertices, indices, sizes, labels, variant="fast")
    with pytest.raises(ValueError, match="tolerance"):
        native.deform(vertices, indices, sizes, labels, tolerance=-1)
    with pytest.raises(ValueError, match="iteration"):
        native.deform(vertices, indices, sizes, labels, iterations=-3)


def test_fandisk_both_variants_finite(native, real_mesh):
    vertices, indices, sizes = real_mesh("fandisk")
    labels = native.nearest_labels(vertices, indices, sizes)
    for variant in ("fixed", "current"):
        result = native.deform(vertices, indices, sizes, labels, iterations=30, variant=variant)
        assert np.isfinite(result["positions"]).all()
        assert result["report"]["triangles"] == 12946


def test_variants_and_defaults_are_published(native):
    assert native.VARIANTS[0] == native.DEFAULT_VARIANT == "robust"
    assert set(native.VARIANTS) == {"robust", "fixed", "current"}
    assert 0 < native.DEFAULT_COMPACTNESS


def test_face_lists_hold_every_id(native):
    # Every face asked to face +Z: past a thousand unconverged faces, which the
    # JSON report would cut short; the module lists them all.
    vertices, face_indices, face_sizes = uv_sphere(segments=96, rings=48)
    labels = np.full(len(face_sizes), 4, dtype=np.int32)
    report = native.deform(vertices, face_indices, face_sizes, labels, iterations=2, tolerance=0.01,
                           variant="fixed")["report"]
    assert report["unconverged_faces_count"] > 1000
    for key in ("unconverged_faces", "flipped_face_ids", "relabelled_faces"):
        ids = np.asarray(report[key])
        assert len(ids) == report[f"{key}_count"], key
        assert np.all(np.diff(ids) > 0), key


# Strict conversion at the boundary: a value that would change in a cast is refused, naming the argument.
@pytest.mark.parametrize("mutate, error, words", [
    (lambda v, i, s, l: (v, i.astype(np.int64) + 2**32, s, l), ValueError,
     r"face_indices\[0\] is 4294967296, outside the vertex indices 0\.\.481"),
    (lambda v, i, s, l: (v, np.full(len(i), 2**63, dtype=np.uint64), s, l), ValueError,
     r"face_indices\[0\] is 9223372036854775808, outside"),
    (lambda v, i, s, l: (v, i - 0.1, s, l), TypeError, "face_indices must hold integers, got dtype float64"),
    (lambda v, i, s, l: (v, i, s.astype(np.float32), l), TypeError, "face_sizes must hold integers"),
    (lambda v, i, s, l: (v, i, s, l + 0.7), TypeError, "labels must hold integers, got dtype float64"),
    (lambda v, i, s, l: (v, i, s, l.astype(bool)), TypeError, "labels must hold integers, got dtype bool"),
    (lambda v, i, s, l: (v, i, s, np.where(np.arange(len(l)) == 3, 2**32 + 2, l)), ValueError,
     r"labels\[3\] is 4294967298, outside -1\.\.5"),
    (lambda v, i, s, l: (v, i, s, l.astype(np.uint8) + 250), ValueError, r"labels\[0\] is 25[0-5], outside -1\.\.5"),
    (lambda v, i, s, l: (v, i, s, np.array(["a"] * len(l))), TypeError, "labels must hold integers"),
    (lambda v, i, s, l: (v, i, s.astype(np.uint64) - 3, l), ValueError, r"face_sizes\[0\] is 0, outside 3\.\."),
])
@pytest.mark.parametrize("function", ["deform", "validate_labels", "refine", "figures"])
def test_no_silent_conversion(native, sphere, mutate, error, words, function):
    vertices, indices, sizes = sphere
    labels = native.nearest_labels(vertices, indices, sizes)
    v, i, s, l = mutate(vertices, indices, sizes, labels)
    calls = {
        "deform": lambda: native.deform(v, i, s, l, iterations=1),
        "validate_labels": lambda: native.validate_labels(v, i, s, l),
        "refine": lambda: native.refine(v, i, s, l),
        "figures": lambda: native.figures(v, v, i, s, l),
    }
    with pytest.raises(error, match=words):
        calls[function]()


def test_integer_arrays_of_any_width_and_lists_are_taken(native, sphere):
    vertices, indices, sizes = sphere
    labels = native.nearest_labels(vertices, indices, sizes)
    expected = native.validate_labels(vertices, indices, sizes, labels)
    for dtype in (np.int16, np.int64, np.uint32, np.uint64):
        assert native.validate_labels(vertices, indices.astype(dtype), sizes.astype(dtype),
                                      labels.astype(np.int64)) == expected
    assert native.validate_labels(vertices, list(indices), list(sizes), list(labels)) == expected


def test_callback_must_return_a_bool(native, sphere):
    vertices, indices, sizes = sphere
    labels = native.nearest_labels(vertices, indices, sizes)
    with pytest.raises(TypeError, match="callback must return True .go on., False .stop. or None, got str"):
        native.deform(vertices, indices, sizes, labels, iterations=3, callback=lambda k, x, f: "yes")
    stopped = native.deform(vertices, indices, sizes, labels, iterations=3, callback=lambda k, x, f: np.bool_(k < 2))
    assert stopped["report"]["iterations"] == 2 and stopped["report"]["stopped"] is True


def test_figures_refuse_non_finite_output(native, sphere):
    vertices, indices, sizes = sphere
    labels = native.nearest_labels(vertices, indices, sizes)
    for bad in (np.nan, np.inf):
        output = vertices.copy()
        output[5, 1] = bad
        with pytest.raises(ValueError, match=r"output_vertices\[5\] is not finite"):
            native.figures(vertices, output, indices, sizes, labels)


def test_flip_labels_checks_its_range(native):
    assert list(native.flip_labels([0, 1, 2, 3, 4, 5, -1])) == [1, 0, 3, 2, 5, 4, -1]
    with pytest.raises(ValueError, match=r"labels\[0\] is 9, outside -1\.\.5"):
        native.flip_labels([9, 6, 100])


def test_read_labels_and_nul_in_paths(native, tmp_path):
    path = tmp_path / "l.txt"
    path.write_text("0\n5\n-1\n")
    assert list(native.read_labels(str(path), 3)) == [0, 5, -1]
    path.write_text("0\n2.7\n-1\n")
    with pytest.raises(ValueError, match=r"line 2: expected an integer label, got '2.7'"):
        native.read_labels(str(path), 3)
    for call in (lambda p: native.read_mesh(p), lambda p: native.read_labels(p, 3)):
        with pytest.raises(ValueError, match=r"the path '.*l\.txt\?x\.off' contains a NUL character"):
            call(str(path) + "\0x.off")
