"""Labels in Blender: Auto Label (attribute and face maps, its own maps only),
Validate Labels (exactly the offending faces selected), label colours, the deform
operator's label source, selecting unconverged faces, and undo."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    add_attribute, add_face_maps, arrays, cube_with_nine_faces_a_side, deform, enable_addon, face_map_of_face,
    key_figures, key_names, nearest_axis_labels, report, run_tests, select_only, uv_sphere)

polycube = enable_addon()
from polycube.label_cache import label_summary  # noqa: E402
from polycube.label_colours import LABEL_COLOURS, NEAREST_COLOURS  # noqa: E402
from polycube.validation import load_validation  # noqa: E402

NAMES = polycube.polycube_native.LABEL_NAMES


def _auto_label(*objects, **settings):
    select_only(*objects)
    return bpy.ops.object.polycube_auto_label(**settings)


def _int_attribute(obj, name):
    values = np.empty(len(obj.data.polygons), dtype=np.int32)
    obj.data.attributes[name].data.foreach_get("value", values)
    return values


def _selected_faces(obj):
    flags = np.empty(len(obj.data.polygons), dtype=bool)
    obj.data.polygons.foreach_get("select", flags)
    return np.flatnonzero(flags)


def _expected_auto_labels(obj, **settings):
    mesh = arrays(obj)
    return np.asarray(polycube.polycube_native.auto_labels(
        mesh.vertices, mesh.face_indices, mesh.face_sizes, **settings))


def _edge_neighbours(obj, face):
    """Faces sharing an edge with `face`, found from Blender's edge keys."""
    edges = set(obj.data.polygons[face].edge_keys)
    return {p.index for p in obj.data.polygons if p.index != face and edges & set(p.edge_keys)}


def test_auto_label_writes_the_attribute_and_face_maps():
    sphere = uv_sphere()
    assert _auto_label(sphere, detail=0.3) == {'FINISHED'}
    labels = _int_attribute(sphere, "polycube_label")
    assert np.array_equal(labels, _expected_auto_labels(sphere, detail=0.3))
    assert sorted(np.unique(labels).tolist()) == list(range(6))
    # One face map per label, named +X ... -Z, holding exactly the faces of that label.
    assert sorted(face_map.name for face_map in sphere.face_maps) == sorted(NAMES)
    maps = face_map_of_face(sphere)
    assert maps == [NAMES[label] for label in labels]
    assert polycube.labels.read_labels(sphere).source == "attribute polycube_label"
    # The labels were validated on the way: the sidebar's figures are there.
    validation = load_validation(sphere, label_summary(sphere).digest)
    assert validation["valid"] == 1 and validation["violations"] == 0, validation
    assert (validation["charts"], validation["corners"]) == (6, 8), validation


def test_a_second_run_replaces_only_its_own_face_maps():
    sphere = uv_sphere()
    faces = len(sphere.data.polygons)
    notes = sphere.face_maps.new(name="Notes")
    notes.add([0, 1, 2])
    _auto_label(sphere)
    # Spoil our maps (everything else in +X) and add a label map of another spelling.
    px = sphere.face_maps.new(name="PX")
    px.add(list(range(3, 40)))
    sphere.face_maps["+X"].add(list(range(40, faces)))
    _auto_label(sphere)

    labels = _int_attribute(sphere, "polycube_label")
    assert np.array_equal(labels, _expected_auto_labels(sphere))
    maps = face_map_of_face(sphere)
    assert maps[:3] == ["Notes"] * 3 and maps.count("Notes") == 3  # the user's map, untouched
    assert maps[3:] == [NAMES[label] for label in labels[3:]]
    names = [face_map.name for face_map in sphere.face_maps]
    assert names.count("+X") == 1 and "Notes" in names and "+X.001" not in names, names
    assert "PX" not in maps  # its faces moved to our maps; the (now empty) map is the user's
    assert sorted(set(maps) - {"Notes"}) == sorted(NAMES)


def test_auto_label_is_undone_in_one_step():
    sphere = uv_sphere()
    # Background Blender pushes no undo step after an operator called from Python.
    bpy.ops.ed.undo_push(message="before auto label")
    _auto_label(sphere)
    bpy.ops.ed.undo_push(message="Auto Label")
    bpy.ops.ed.undo()
    sphere = bpy.data.objects["Sphere"]
    assert "polycube_label" not in sphere.data.attributes
    assert len(sphere.face_maps) == 0 and "polycube_validation" not in sphere.keys()
    bpy.ops.ed.redo()
    sphere = bpy.data.objects["Sphere"]
    assert "polycube_label" in sphere.data.attributes and len(sphere.face_maps) == 6


def test_validation_selects_exactly_the_offending_faces():
    cube = cube_with_nine_faces_a_side()
    labels = nearest_axis_labels(cube)
    centres = np.array([p.center for p in cube.data.polygons])
    centre = int(np.flatnonzero((labels == 4) & (np.abs(centres[:, :2]).max(axis=1) < 0.1))[0])
    labels[centre] = 5  # the middle of the top, labelled -Z: one chart inside its opposite
    add_face_maps(cube, labels, NAMES)
    expected = sorted({centre} | _edge_neighbours(cube, centre))
    assert len(expected) == 5

    select_only(cube)
    assert bpy.ops.object.polycube_validate_labels() == {'FINISHED'}
    assert cube.mode == 'EDIT'
    assert tuple(bpy.context.tool_settings.mesh_select_mode) == (False, False, True)
    bpy.ops.object.mode_set(mode='OBJECT')
    assert _selected_faces(cube).tolist() == expected
    selected_vertices = np.empty(len(cube.data.vertices), dtype=bool)
    cube.data.vertices.foreach_get("select", selected_vertices)
    corners = {v for face in expected for v in cube.data.polygons[face].vertices}
    assert np.flatnonzero(selected_vertices).tolist() == sorted(corners)

    validation = load_validation(cube, label_summary(cube).digest)
    assert validation["valid"] == 0 and validation["charts"] == 7, validation
    # The -Z face inside the +Z top also faces away from its axis.
    assert validation["kinds"] == {"too_few_neighbours": 1, "opposite_neighbours": 1, "reversed_chart": 1}, validation


def test_validation_of_good_labels_selects_nothing_and_goes_stale_when_they_change():
    cube = cube_with_nine_faces_a_side()
    labels = nearest_axis_labels(cube).astype(np.int32)
    add_attribute(cube.data, "polycube_label", 'INT', labels)
    select_only(cube)
    assert bpy.ops.object.polycube_validate_labels() == {'FINISHED'}
    assert cube.mode == 'OBJECT'
    validation = load_validation(cube, label_summary(cube).digest)
    assert (validation["valid"], validation["charts"], validation["corners"]) == (1, 6, 8), validation
    cube.data.attributes["polycube_label"].data[0].value = (labels[0] + 2) % 6
    bpy.context.view_layer.update()
    assert load_validation(cube, label_summary(cube).digest) is None  # the sidebar says: not validated


def test_validation_names_an_inward_wound_mesh_and_labels_for_the_other_winding():
    sphere = uv_sphere()
    outward = nearest_axis_labels(sphere).astype(np.int32)
    select_only(sphere)
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    bpy.ops.mesh.flip_normals()
    bpy.ops.object.mode_set(mode='OBJECT')
    add_attribute(sphere.data, "polycube_label", 'INT', outward)
    assert bpy.ops.object.polycube_validate_labels() == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')  # validation showed the reversed charts in Edit Mode
    validation = load_validation(sphere, label_summary(sphere).digest)
    # Chart topology is fine, but against this winding every chart faces away from its axis.
    assert validation["valid"] == 0 and validation["kinds"]["reversed_chart"] == 6, validation
    assert validation["orientation"] == ["Wound inward", "Labels for the opposite winding"], validation
    # Labels made for this winding (auto labels follow the normals): only the winding is named.
    _auto_label(sphere)
    validation = load_validation(sphere, label_summary(sphere).digest)
    assert validation["orientation"] == ["Wound inward"], validation
    cube = cube_with_nine_faces_a_side()
    add_attribute(cube.data, "polycube_label", 'INT', nearest_axis_labels(cube).astype(np.int32))
    select_only(cube)
    bpy.ops.object.polycube_validate_labels()
    assert load_validation(cube, label_summary(cube).digest)["orientation"] == []


def test_validation_from_edit_mode_and_its_undo():
    cube = cube_with_nine_faces_a_side()
    labels = nearest_axis_labels(cube)
    labels[0] = {0: 1, 1: 0, 2: 3, 3: 2, 4: 5, 5: 4}[int(labels[0])]
    add_attribute(cube.data, "polycube_label", 'INT', labels.astype(np.int32))
    select_only(cube)
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    bpy.ops.ed.undo_push(message="everything selected")
    assert bpy.ops.object.polycube_validate_labels() == {'FINISHED'}
    bpy.ops.ed.undo_push(message="Validate Labels")
    bpy.ops.object.mode_set(mode='OBJECT')
    assert 0 < len(_selected_faces(cube)) < 10
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.ed.undo()
    bpy.ops.object.mode_set(mode='OBJECT')
    cube = bpy.data.objects[cube.name]
    assert len(_selected_faces(cube)) == 54


def test_label_colours_match_the_labels_and_leave_the_users_colours_alone():
    sphere = uv_sphere()
    mesh = sphere.data
    paint = mesh.color_attributes.new("Paint", 'FLOAT_COLOR', 'POINT')
    painted = np.random.default_rng(1).random(len(mesh.vertices) * 4).astype(np.float32)
    paint.data.foreach_set("color", painted)
    mesh.color_attributes.active_color = paint
    _auto_label(sphere)
    assert bpy.ops.object.polycube_label_colours() == {'FINISHED'}

    colours = mesh.color_attributes["polycube_label_colour"]
    assert (colours.domain, colours.data_type) == ('CORNER', 'BYTE_COLOR')
    assert mesh.color_attributes.active_color.name == "polycube_label_colour"
    labels = _int_attribute(sphere, "polycube_label")
    values = np.empty(len(mesh.loops) * 4, dtype=np.float32)
    colours.data.foreach_get("color", values)
    face_of_loop = np.repeat(np.arange(len(mesh.polygons)), [p.loop_total for p in mesh.polygons])
    assert np.abs(values.reshape(-1, 4) - LABEL_COLOURS[labels[face_of_loop]]).max() < 0.01
    assert len(np.unique(np.round(values.reshape(-1, 4), 2), axis=0)) == 6  # six distinct colours

    # Relabelling refreshes colours that are shown.
    add_attribute(mesh, "polycube_label", 'INT', np.full(len(labels), 2, np.int32))
    _auto_label(sphere, detail=0.3)
    colours.data.foreach_get("color", values)
    labels = _int_attribute(sphere, "polycube_label")
    assert np.abs(values.reshape(-1, 4) - LABEL_COLOURS[labels[face_of_loop]]).max() < 0.01

    assert bpy.ops.object.polycube_label_colours(show=False) == {'FINISHED'}
    assert "polycube_label_colour" not in mesh.color_attributes
    assert mesh.color_attributes.active_color.name == "Paint"
    now = np.empty(len(painted), dtype=np.float32)
    mesh.color_attributes["Paint"].data.foreach_get("color", now)
    assert np.array_equal(now, painted)


def test_label_colours_paint_unlabelled_faces_their_nearest_axis_pale():
    sphere = uv_sphere()
    nearest = nearest_axis_labels(sphere)
    stored = nearest.copy()
    stored[::3] = -1  # every third face unlabelled
    stored[1::6] = 4  # and some labelled +Z, where the nearest axis is another
    add_attribute(sphere.data, "polycube_label", 'INT', stored.astype(np.int32))
    select_only(sphere)
    assert bpy.ops.object.polycube_label_colours() == {'FINISHED'}
    mesh = sphere.data
    values = np.empty(len(mesh.loops) * 4, dtype=np.float32)
    mesh.color_attributes["polycube_label_colour"].data.foreach_get("color", values)
    starts = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("loop_start", starts)
    shown = values.reshape(-1, 4)[starts]
    expected = np.where((stored < 0)[:, None], NEAREST_COLOURS[nearest], LABEL_COLOURS[stored])
    assert np.abs(shown - expected).max() < 0.01
    # Pale: every pale color is far from every label color, and lighter than its own.
    distances = np.abs(NEAREST_COLOURS[:, None, :3] - LABEL_COLOURS[None, :, :3]).max(axis=2)
    assert distances.min() > 0.15, distances
    assert (NEAREST_COLOURS[:, :3].sum(axis=1) > LABEL_COLOURS[:, :3].sum(axis=1) + 0.5).all()


def test_label_source_automatic_on_an_unlabelled_sphere():
    sphere = uv_sphere()
    assert deform(sphere, iterations=200, label_source='AUTO') == {'FINISHED'}
    result = report(sphere)
    assert result["label_source"] == "automatic" and result["unlabelled_faces"] == 0
    assert result["converged"] and result["flipped_faces"] == 0, result
    labels = _expected_auto_labels(sphere, detail=bpy.context.scene.polycube.detail)
    final = key_figures(sphere, key_names(sphere)[-1], labels)
    assert final["flipped_faces"] == 0 and final["normal_deviation_max_deg"] < 0.5, final
    # The labels were computed for the run, not written to the mesh.
    assert "polycube_label" not in sphere.data.attributes and len(sphere.face_maps) == 0


def test_label_source_automatic_where_unlabelled_keeps_the_stored_labels():
    sphere = uv_sphere()
    stored = np.full(len(sphere.data.polygons), -1)
    stored[:64] = 1  # the first rings, all -X: a label the labeller would not choose there
    add_face_maps(sphere, stored, NAMES)
    deform(sphere, iterations=2, label_source='AUTO_UNLABELLED')
    result = report(sphere)
    assert result["label_source"] == "face maps, automatic where unlabelled", result["label_source"]
    expected = np.where(stored >= 0, stored, _expected_auto_labels(sphere))
    assert result["label_counts"] == dict(zip(NAMES, np.bincount(expected, minlength=6).tolist()))
    assert result["unlabelled_faces"] == 0


def test_select_unconverged_faces():
    sphere = uv_sphere()
    add_attribute(sphere.data, "polycube_label", 'INT', np.full(len(sphere.data.polygons), 4, np.int32))
    deform(sphere, iterations=3, tolerance=1e-4, variant='FIXED')
    result = report(sphere)
    unconverged = polycube.report.report_faces(sphere, "unconverged_faces")
    assert result["unconverged_faces_count"] == len(unconverged) > 0, result
    assert "unconverged_faces" not in result  # kept apart from the report the sidebar reads
    select_only(sphere)
    assert bpy.ops.object.polycube_select_unconverged() == {'FINISHED'}
    assert sphere.mode == 'EDIT'
    bpy.ops.object.mode_set(mode='OBJECT')
    assert _selected_faces(sphere).tolist() == sorted(unconverged.tolist())


def _validation(obj, labels):
    mesh = arrays(obj)
    return polycube.polycube_native.validate_labels(mesh.vertices, mesh.face_indices, mesh.face_sizes, labels)


def _loose_parts(obj):
    """Per face, the index of its loose part (faces joined through shared vertices)."""
    parent = list(range(len(obj.data.vertices)))

    def root(v):
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v
    for polygon in obj.data.polygons:
        for v in polygon.vertices[1:]:
            a, b = root(polygon.vertices[0]), root(v)
            parent[max(a, b)] = min(a, b)
    return [root(polygon.vertices[0]) for polygon in obj.data.polygons]


def test_suzanne_eyes_are_one_chart_each_and_detail_zero_is_a_head():
    bpy.ops.object.select_all(action='DESELECT')
    bpy.ops.mesh.primitive_monkey_add()
    suzanne = bpy.context.active_object
    parts = _loose_parts(suzanne)
    assert len(set(parts)) == 3  # the head and two open eyeballs
    assert _auto_label(suzanne) == {'FINISHED'}
    labels = _int_attribute(suzanne, "polycube_label")
    head = max(set(parts), key=parts.count)
    for eye in set(parts) - {head}:
        assert len({labels[f] for f in range(len(parts)) if parts[f] == eye}) == 1
    default = _validation(suzanne, labels)
    # What a modeller would draw: head, muzzle, ears and eyes, no one-face charts.
    assert default["valid"] and default["charts"] <= 20, default
    # The coarse end of Detail: no more charts than the default.
    assert _auto_label(suzanne, detail=0.0) == {'FINISHED'}
    coarse = _validation(suzanne, _int_attribute(suzanne, "polycube_label"))
    assert coarse["valid"] and coarse["charts"] <= default["charts"], coarse
    # The sidebar's figures follow the new labels.
    assert load_validation(suzanne, label_summary(suzanne).digest)["charts"] == coarse["charts"]
    assert deform(suzanne, label_source='STORED') == {'FINISHED'}
    figures = key_figures(suzanne, suzanne.data.shape_keys.key_blocks[-1].name,
                          _int_attribute(suzanne, "polycube_label"))
    assert figures["flipped_faces"] == 0 and figures["normal_deviation_max_deg"] < 0.5, figures


def test_suzanne_with_subdivision_level_2_is_as_simple_as_suzanne():
    # The same shape meshed 16 times finer: the straightening smooths over
    # the same share of the surface, so the charts stay those of a head
    # (docs/design.md section 3.4). At a fixed number of rings it had 36.
    bpy.ops.object.select_all(action='DESELECT')
    bpy.ops.mesh.primitive_monkey_add()
    suzanne = bpy.context.active_object
    suzanne.modifiers.new("Subdivision", 'SUBSURF').levels = 2
    bpy.ops.object.modifier_apply(modifier="Subdivision")
    assert len(suzanne.data.polygons) == 7872
    assert _auto_label(suzanne) == {'FINISHED'}
    labels = _int_attribute(suzanne, "polycube_label")
    validation = _validation(suzanne, labels)
    assert validation["valid"] and validation["charts"] <= 20, validation
    assert deform(suzanne, label_source='STORED') == {'FINISHED'}
    figures = key_figures(suzanne, suzanne.data.shape_keys.key_blocks[-1].name, labels)
    assert figures["flipped_faces"] == 0 and figures["normal_deviation_max_deg"] < 0.5, figures
    assert figures["collapsed_area"] < 0.02, figures


def test_operators_are_registered_undoable():
    for name in ("polycube_auto_label", "polycube_validate_labels", "polycube_label_colours",
                 "polycube_select_unconverged"):
        cls = getattr(bpy.types, f"OBJECT_OT_{name}")
        assert {'REGISTER', 'UNDO'} <= set(cls.bl_options), name
    scene = bpy.context.scene.polycube
    operator = bpy.ops.object.polycube_auto_label.get_rna_type().properties
    assert scene.detail == operator["detail"].default
    assert scene.label_source == 'STORED'


run_tests(globals())
