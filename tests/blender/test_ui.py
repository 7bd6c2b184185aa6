"""The add-on in Blender's real window (run.py starts this under Xvfb, not -b).

The Polycube sidebar tab is opened the way a user does it (wheel over the tabs,
through simulated events), the panel must draw, the button's modal run must keep
Blender's event loop going while it writes iterations, Esc must stop it keeping
what is written, and one undo must take the run back. A screenshot of the
window with the panel is kept at build/ui/polycube-panel.png.

Blender's event loop has to run for all of this, so the tests are generators
stepped from a timer: each `yield` hands control back to Blender for that many
seconds.
"""

import os
import sys
import threading
import time
import traceback

import bmesh
import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    RESULT_PREFIX, ROOT, add_attribute, enable_addon, key_names, labelled_sphere, report, select_only, uv_sphere)

polycube = enable_addon()
SCREENSHOT = os.path.join(ROOT, "build", "ui", "polycube-panel.png")
SCRIPT = os.path.basename(__file__)

def _record_draws(cls, record):
    """Wrap cls.draw (the add-on has no test hooks): after each draw that did not
    raise, append record(context) to the returned list."""
    draws, draw = [], cls.draw

    def recording_draw(self, context):
        draw(self, context)  # an exception here means no record: it failed to draw
        draws.append(record(context))

    cls.draw = recording_draw
    return draws


def _object_and_report(context):
    obj = context.active_object
    return obj.name if obj else None, obj is not None and report(obj) is not None


panel_draws = _record_draws(bpy.types.VIEW3D_PT_polycube, _object_and_report)
label_draws = _record_draws(bpy.types.VIEW3D_PT_polycube_labels, lambda context: context.mode)
pie_draws = _record_draws(bpy.types.VIEW3D_MT_polycube_label_pie, lambda context: context.mode)
PIE_SCREENSHOT = os.path.join(ROOT, "build", "ui", "polycube-edit-mode-pie.png")
REDO_SCREENSHOT = os.path.join(ROOT, "build", "ui", "polycube-redo.png")


def _view3d():
    window = bpy.context.window_manager.windows[0]
    area = next(area for area in window.screen.areas if area.type == 'VIEW_3D')
    regions = {region.type: region for region in area.regions}
    return window, area, regions["WINDOW"], regions["UI"]


def _override():
    window, area, region, _ = _view3d()
    return bpy.context.temp_override(window=window, area=area, region=region)


def _wait_until(condition, what, timeout=60.0):
    start = time.monotonic()
    while not condition():
        if time.monotonic() - start > timeout:
            raise AssertionError(f"timed out waiting for {what}")
        yield 0.1


def _redraw():
    for area in bpy.context.window_manager.windows[0].screen.areas:
        area.tag_redraw()


def _open_polycube_tab():
    """Show the sidebar on the Polycube tab, as a user does (a no-op once open)."""
    window, area, _, sidebar = _view3d()
    if not panel_draws:
        window.event_simulate(type='ESC', value='PRESS')  # close the splash screen
        window.event_simulate(type='ESC', value='RELEASE')
    area.spaces.active.show_region_ui = True
    yield 0.5
    for _ in range(10):  # Item, Tool, View, ... : wheel over the tabs to reach Polycube
        if panel_draws:
            break
        _, _, _, sidebar = _view3d()
        x, y = sidebar.x + sidebar.width - 8, sidebar.y + sidebar.height // 2
        window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
        window.event_simulate(type='WHEELDOWNMOUSE', value='PRESS', x=x, y=y, ctrl=True)
        yield 0.3
    assert panel_draws, "the Polycube panel never drew"


def test_sidebar_tab_draws_the_panel():
    labelled_sphere("Panel sphere")
    yield from _open_polycube_tab()
    assert panel_draws[-1][0] == "Panel sphere"


def test_button_run_is_modal_and_pushes_its_undo_step():
    labelled_sphere("Modal sphere")
    # Operators called from Python push no undo step (the caller would); record the
    # sphere's creation so that one undo can only take back the operator's own step.
    bpy.ops.ed.undo_push(message="Add labelled sphere")
    with _override():
        assert bpy.ops.object.polycube_deform('INVOKE_DEFAULT', iterations=200) == {'RUNNING_MODAL'}
    yield from _wait_until(lambda: report(bpy.data.objects["Modal sphere"]) is not None, "the modal run")
    sphere = bpy.data.objects["Modal sphere"]
    result = report(sphere)
    assert result["converged"] and result["normal_deviation_max_deg"] < 0.5, result
    # Solve time is the solver's (its phases), not the time the UI took to write keys.
    seconds = result["seconds"]
    phases = sum(seconds[phase] for phase in ("assemble", "factorize", "rotations", "solve", "measure"))
    assert seconds["deform_call"] < phases + 0.25, seconds
    assert key_names(sphere) == ["Basis"] + [f"Polycube {k:03d}" for k in range(1, result["iterations"] + 1)]
    yield 0.2

    with _override():
        bpy.ops.ed.undo()
    sphere = bpy.data.objects["Modal sphere"]  # still there: only the run was undone
    assert sphere.data.shape_keys is None and report(sphere) is None
    assert len(sphere.face_maps) == 6
    with _override():
        bpy.ops.ed.redo()
    assert report(bpy.data.objects["Modal sphere"])["converged"]


def test_long_run_keeps_blender_responsive_and_esc_keeps_iterations():
    big = uv_sphere("Big sphere", segments=64, rings=32)
    # Every face asked to face +Z: a fold no iteration can undo, so the run goes on
    # until stopped.
    add_attribute(big.data, "polycube_label", 'INT', np.full(len(big.data.polygons), 4, np.int32))
    select_only(big)
    with _override():
        bpy.ops.object.polycube_deform('INVOKE_DEFAULT', iterations=100000)
    counts = []
    for _ in range(400):  # each step is Blender's event loop coming back to this timer
        counts.append(len(key_names(big)))
        if counts[-1] > 15:
            break
        yield 0.05
    assert report(big) is None, "the run ended by itself"
    assert len(set(counts)) >= 3, f"no progress seen between timer steps: {counts}"
    window = _view3d()[0]
    window.event_simulate(type='ESC', value='PRESS')
    window.event_simulate(type='ESC', value='RELEASE')
    yield from _wait_until(lambda: report(big) is not None, "the run to stop after Esc")
    result = report(big)
    assert result["stopped"] and not result["converged"], result
    assert counts[-1] - 1 <= result["iterations"] < 1000, result["iterations"]
    # A key for every iteration that moved the mesh.
    kept = result["kept_iterations"]
    assert key_names(big)[1:] == [f"Polycube {k:06d}" for k in kept]
    assert kept == sorted(set(kept)) and kept[-1] <= result["iterations"] and len(kept) >= counts[-1] - 1
    assert big.data.shape_keys.key_blocks[-1].value == 1.0


def test_labels_and_subdivision_run_off_the_ui_thread_and_esc_changes_nothing():
    sphere = uv_sphere("Prepared sphere")
    select_only(sphere)
    # A labeller and a refinement that work until the test lets them finish, as on a
    # detailed model; each notes whether it ran on Blender's main thread.
    label_source, subdivide = polycube.label_source, polycube.subdivide
    labeller, refiner = label_source.automatic_labels, subdivide.refine
    release, on_main_thread = threading.Event(), []

    def held(function):
        def call(*args, **kwargs):
            on_main_thread.append(threading.current_thread() is threading.main_thread())
            release.wait(30)
            return function(*args, **kwargs)
        return call

    label_source.automatic_labels, subdivide.refine = held(labeller), held(refiner)
    settings = dict(label_source='AUTO', subdivide=True, iterations=100)
    try:
        with _override():
            assert bpy.ops.object.polycube_deform('INVOKE_DEFAULT', **settings) == {'RUNNING_MODAL'}
        for _ in range(5):  # Blender's event loop goes on while the labeller works
            yield 0.1
        assert on_main_thread == [False], on_main_thread
        window = _view3d()[0]
        window.event_simulate(type='ESC', value='PRESS')
        window.event_simulate(type='ESC', value='RELEASE')
        yield 0.3
        release.set()  # labeller and refinement end after Esc: their results are dropped
        yield 1.0
        assert on_main_thread == [False, False], on_main_thread
        assert "Prepared sphere polycube" not in bpy.data.objects
        assert sphere.data.shape_keys is None and report(sphere) is None
        assert "polycube_label" not in sphere.data.attributes
    finally:
        release.set()
        label_source.automatic_labels, subdivide.refine = labeller, refiner

    select_only(sphere)
    with _override():
        assert bpy.ops.object.polycube_deform('INVOKE_DEFAULT', **settings) == {'RUNNING_MODAL'}
    copy = lambda: bpy.data.objects.get("Prepared sphere polycube")  # noqa: E731
    yield from _wait_until(lambda: copy() is not None and report(copy()) is not None, "the prepared run")
    result = report(copy())
    assert result["label_source"] == "automatic, subdivided (bilinear x1)", result["label_source"]
    # Bilinear subdivision splits each n-sided face into n quads: a face per corner.
    assert len(copy().data.polygons) == len(sphere.data.loops)
    assert sphere.data.shape_keys is None


def test_redo_panel_says_how_long_a_change_takes():
    sphere = labelled_sphere("Redo sphere")
    for obj in bpy.context.scene.objects:
        obj.hide_set(obj.type == 'MESH' and obj != sphere)
    select_only(sphere)
    with _override():
        assert bpy.ops.object.polycube_deform('INVOKE_DEFAULT', iterations=200) == {'RUNNING_MODAL'}
    yield from _wait_until(lambda: report(sphere) is not None, "the modal run")
    yield 0.2
    operator = bpy.context.window_manager.operators[-1]
    assert operator.bl_idname == "OBJECT_OT_polycube_deform", operator.bl_idname
    expected = polycube.report.work_seconds(report(sphere))
    assert 0 < expected and abs(operator.properties.last_seconds - expected) < 1e-4, \
        (operator.properties.last_seconds, expected)
    # F9 opens the redo panel as a popup: it draws the operator with the estimate.
    estimates, estimate_text = [], polycube.redo_estimate.estimate_text
    polycube.redo_estimate.estimate_text = lambda seconds: estimates.append(estimate_text(seconds)) or estimates[-1]
    try:
        window, _, region, _ = _view3d()
        x, y = region.x + region.width // 2, region.y + region.height // 2
        window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
        window.event_simulate(type='F9', value='PRESS', x=x, y=y)
        window.event_simulate(type='F9', value='RELEASE', x=x, y=y)
        yield from _wait_until(lambda: estimates, "the redo panel's estimate")
        _screenshot(REDO_SCREENSHOT)
        window.event_simulate(type='ESC', value='PRESS', x=x, y=y)
        window.event_simulate(type='ESC', value='RELEASE', x=x, y=y)
        yield 0.2
    finally:
        polycube.redo_estimate.estimate_text = estimate_text
    assert estimates[-1] == f"Each change runs it again: about {expected:.1f} s", estimates[-1]


def test_panel_shows_the_last_run_and_screenshot():
    sphere = labelled_sphere("Shown sphere")
    for obj in bpy.context.scene.objects:  # the earlier tests' spheres are in the same place
        obj.hide_set(obj.type == 'MESH' and obj != sphere)
    select_only(sphere)
    with _override():
        # Labels, their validation and colours too, so the screenshot shows the whole panel.
        assert bpy.ops.object.polycube_auto_label() == {'FINISHED'}
        assert bpy.ops.object.polycube_label_colours() == {'FINISHED'}
        bpy.ops.object.polycube_deform(iterations=200, animate=True)
    assert _view3d()[1].spaces.active.shading.color_type == 'VERTEX'
    assert sphere.data.color_attributes.active_color.name == "polycube_label_colour"
    panel_draws.clear()
    _redraw()
    yield from _wait_until(lambda: ("Shown sphere", True) in panel_draws, "the panel with a report")
    yield 0.3
    os.makedirs(os.path.dirname(SCREENSHOT), exist_ok=True)
    window = _view3d()[0]
    with bpy.context.temp_override(window=window, screen=window.screen):
        bpy.ops.screen.screenshot(filepath=SCREENSHOT)
    assert os.path.getsize(SCREENSHOT) > 10000
    image = bpy.data.images.load(SCREENSHOT)
    width, height = image.size
    pixels = np.empty(width * height * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    _, _, _, sidebar = _view3d()
    crop = pixels.reshape(height, width, 4)[sidebar.y:sidebar.y + sidebar.height,
                                            sidebar.x:sidebar.x + sidebar.width, :3]
    # Text and widgets, not an empty region: many distinct shades.
    assert len(np.unique(np.round(crop.reshape(-1, 3), 2), axis=0)) > 50
    assert sphere.polycube_scrub == 1.0


def _screenshot(path):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    window = _view3d()[0]
    with bpy.context.temp_override(window=window, screen=window.screen):
        bpy.ops.screen.screenshot(filepath=path)
    assert os.path.getsize(path) > 10000


def test_edit_mode_panel_and_label_pie():
    sphere = labelled_sphere("Edited sphere")
    yield from _open_polycube_tab()
    for obj in bpy.context.scene.objects:
        obj.hide_set(obj.type == 'MESH' and obj != sphere)
    select_only(sphere)
    with _override():
        assert bpy.ops.object.polycube_auto_label() == {'FINISHED'}
        assert bpy.ops.object.polycube_label_colours() == {'FINISHED'}
        bpy.ops.object.mode_set(mode='EDIT')
        bpy.ops.mesh.select_all(action='DESELECT')
    # Touch the mesh, as a user editing it does: Edit Mode's attribute data is then empty.
    bm = bmesh.from_edit_mesh(sphere.data)
    bm.faces.ensure_lookup_table()
    for face in list(bm.faces)[:40]:
        face.select_set(True)
    bmesh.update_edit_mesh(sphere.data)
    label_draws.clear()
    _redraw()
    yield from _wait_until(lambda: 'EDIT_MESH' in label_draws, "the Labels panel in Edit Mode")
    with _override():
        assert bpy.ops.mesh.polycube_assign_label(label='-Z') == {'FINISHED'}
    label_draws.clear()
    _redraw()
    yield from _wait_until(lambda: 'EDIT_MESH' in label_draws, "the Labels panel after assigning")
    sphere.scale = (2.5, 2.5, 2.5)  # large in the screenshot; labels are in local axes
    window, area, region, _ = _view3d()
    x, y = region.x + region.width // 4, region.y + region.height // 2  # left of the sphere
    window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    yield 0.2
    # The documented shortcut opens the pie.
    window.event_simulate(type='LEFT_SHIFT', value='PRESS', x=x, y=y)
    window.event_simulate(type='LEFT_ALT', value='PRESS', x=x, y=y, shift=True)
    window.event_simulate(type='L', value='PRESS', x=x, y=y, shift=True, alt=True)
    yield from _wait_until(lambda: pie_draws, "the label pie menu after Shift Alt L")
    # Lean towards +X, as a user choosing it does (the pie redraws with it lit). The pie
    # unfolds and fades in as events reach it: keep them coming for longer than that takes.
    for step in range(10):
        window.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x + 40 + step, y=y, shift=True, alt=True)
        yield 0.1
    _screenshot(PIE_SCREENSHOT)
    # Esc closes the pie without choosing; only then let go of the keys.
    window.event_simulate(type='ESC', value='PRESS', x=x, y=y)
    window.event_simulate(type='ESC', value='RELEASE', x=x, y=y)
    yield 0.2
    for key in ('L', 'LEFT_ALT', 'LEFT_SHIFT'):
        window.event_simulate(type=key, value='RELEASE', x=x, y=y)
    yield 0.2
    with _override():
        bpy.ops.object.mode_set(mode='OBJECT')
    values = np.empty(len(sphere.data.polygons), dtype=np.int32)
    sphere.data.attributes["polycube_label"].data.foreach_get("value", values)
    assert (values[:40] == 5).all()


def test_auto_label_runs_modal_and_esc_leaves_the_labels():
    big = uv_sphere("Label sphere", segments=128, rings=64)
    select_only(big)
    # A labeller that works until the test lets it finish, as on a detailed model.
    operators = polycube.label_operators
    labeller, release = operators.automatic_labels, threading.Event()
    operators.automatic_labels = lambda *args: (release.wait(30), labeller(*args))[1]
    try:
        with _override():
            assert bpy.ops.object.polycube_auto_label('INVOKE_DEFAULT') == {'RUNNING_MODAL'}
        for _ in range(5):  # Blender's event loop goes on while the labeller works
            yield 0.1
        assert "polycube_label" not in big.data.attributes
        window = _view3d()[0]
        window.event_simulate(type='ESC', value='PRESS')
        window.event_simulate(type='ESC', value='RELEASE')
        yield 0.3
        release.set()  # the labeller ends after Esc: its result is dropped, not written
        yield 1.0
        assert "polycube_label" not in big.data.attributes
    finally:
        release.set()
        operators.automatic_labels = labeller

    small = uv_sphere("Labelled sphere")
    select_only(small)
    started = time.monotonic()
    with _override():
        assert bpy.ops.object.polycube_auto_label('INVOKE_DEFAULT') == {'RUNNING_MODAL'}
    yield from _wait_until(lambda: "polycube_label" in small.data.attributes, "the modal Auto Label")
    # The redo panel's estimate: the labeller's time, within the run's.
    operator = bpy.context.window_manager.operators[-1]
    assert operator.bl_idname == "OBJECT_OT_polycube_auto_label", operator.bl_idname
    assert 0 < operator.properties.last_seconds <= time.monotonic() - started, operator.properties.last_seconds
    values = np.empty(len(small.data.polygons), dtype=np.int32)
    small.data.attributes["polycube_label"].data.foreach_get("value", values)
    mesh = polycube.mesh_arrays.read_mesh_arrays(small.data)
    expected = polycube.polycube_native.auto_labels(mesh.vertices, mesh.face_indices, mesh.face_sizes)
    assert values.tolist() == list(expected)


TESTS = [test_sidebar_tab_draws_the_panel, test_button_run_is_modal_and_pushes_its_undo_step,
         test_long_run_keeps_blender_responsive_and_esc_keeps_iterations,
         test_labels_and_subdivision_run_off_the_ui_thread_and_esc_changes_nothing,
         test_redo_panel_says_how_long_a_change_takes,
         test_panel_shows_the_last_run_and_screenshot, test_edit_mode_panel_and_label_pie,
         test_auto_label_runs_modal_and_esc_leaves_the_labels]
wanted = os.environ.get("POLYCUBE_TEST_FILTER", "")
TESTS = [test for test in TESTS if wanted in f"{SCRIPT}::{test.__name__}"]
_state = {"index": 0, "steps": None, "failed": 0}


def _step():
    """Timer: advance the current test generator; report and move on when it ends."""
    if _state["index"] == len(TESTS):
        sys.stdout.flush()
        os._exit(1 if _state["failed"] else 0)
    test = TESTS[_state["index"]]
    try:
        if _state["steps"] is None:
            _state["steps"] = test()
        return next(_state["steps"]) or 0.05
    except StopIteration:
        print(f"{RESULT_PREFIX} PASS {SCRIPT}::{test.__name__}", flush=True)
    except Exception:
        traceback.print_exc()
        print(f"{RESULT_PREFIX} FAIL {SCRIPT}::{test.__name__}", flush=True)
        _state["failed"] += 1
    _state["index"] += 1
    _state["steps"] = None
    return 0.05


bpy.app.timers.register(_step, first_interval=1.0)
