"""Labels from face maps (3.x, every accepted spelling), from what 4.x made of face
maps, and from our own attribute; junk labels refused with one sentence."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    add_attribute, add_face_maps, assert_untouched, deform, deform_error, enable_addon,
    nearest_axis_labels, report, run_tests, uv_sphere, vertices)

polycube = enable_addon()
from polycube.labels import read_labels  # noqa: E402
from polycube.label_cache import label_summary  # noqa: E402

SPELLINGS = {
    "sign first": ("+X", "-X", "+Y", "-Y", "+Z", "-Z"),
    "sign last": ("X+", "X-", "Y+", "Y-", "Z+", "Z-"),
    "letters": ("PX", "NX", "PY", "NY", "PZ", "NZ"),
    "words": ("POS_X", "NEG_X", "POS_Y", "NEG_Y", "POS_Z", "NEG_Z"),
    "lower case": ("px", "nx", "y+", "y-", "pos_z", "neg_z"),
    "mixed case": ("Pos_X", "x-", "pY", "Neg_y", "+z", "Z-"),
}


def test_every_spelling_of_face_maps_gives_the_right_labels():
    for style, names in SPELLINGS.items():
        sphere = uv_sphere(style)
        expected = nearest_axis_labels(sphere)
        add_face_maps(sphere, expected, names)
        labels = read_labels(sphere)
        assert labels.source == "face maps", labels.source
        assert np.array_equal(labels.values, expected), style


def test_face_map_labels_reach_the_solver():
    # A labelling the solver would not guess (+Z everywhere): the report shows it was used.
    sphere = uv_sphere()
    faces = len(sphere.data.polygons)
    add_face_maps(sphere, np.full(faces, 4), SPELLINGS["words"])
    deform(sphere, iterations=2)
    used = report(sphere)
    assert used["label_source"] == "face maps"
    assert used["label_counts"]["+Z"] == faces and used["unlabelled_faces"] == 0


def test_faces_in_no_face_map_are_unlabelled_and_counted():
    sphere = uv_sphere()
    labels = nearest_axis_labels(sphere)
    labels[::3] = -1
    add_face_maps(sphere, labels, SPELLINGS["sign first"])
    assert np.array_equal(read_labels(sphere).values, labels)
    deform(sphere, iterations=200)
    result = report(sphere)
    assert result["unlabelled_faces"] == int((labels == -1).sum())
    assert result["converged"] and result["normal_deviation_max_deg"] < 0.5


def test_blender_4_face_maps_attribute_with_boolean_names():
    sphere = uv_sphere()
    expected = nearest_axis_labels(sphere)
    # Blender 4.0 keeps the map index per face and one boolean per map named after
    # it; the map order need not follow the labels, and unrelated booleans exist.
    map_names = ("Z-", "pos_x", "NY", "+Z", "X-", "POS_Y")
    label_of_map = [5, 0, 3, 4, 1, 2]
    map_of_label = np.argsort(label_of_map)
    add_attribute(sphere.data, "face_maps", 'INT', map_of_label[expected].astype(np.int32))
    for index, name in enumerate(map_names):
        add_attribute(sphere.data, name, 'BOOLEAN', map_of_label[expected] == index)
    add_attribute(sphere.data, "sharp_face", 'BOOLEAN', np.ones(len(expected), dtype=bool))
    labels = read_labels(sphere)
    assert labels.source == "attribute face_maps", labels.source
    assert np.array_equal(labels.values, expected)
    deform(sphere, iterations=200)
    assert report(sphere)["label_counts"] == dict(zip(SPELLINGS["sign first"], np.bincount(expected).tolist()))


def test_blender_4_face_map_without_a_name_is_refused():
    sphere = uv_sphere()
    add_attribute(sphere.data, "face_maps", 'INT', np.zeros(len(sphere.data.polygons), dtype=np.int32))
    before = vertices(sphere)
    message = deform_error(sphere)
    assert "face map 0" in message and "no boolean face attribute" in message, message
    assert_untouched(sphere, before)


def test_our_label_attribute_wins_over_face_maps():
    sphere = uv_sphere()
    expected = nearest_axis_labels(sphere)
    add_face_maps(sphere, np.full(len(expected), 0), SPELLINGS["sign first"])
    add_attribute(sphere.data, "polycube_label", 'INT', expected.astype(np.int32))
    labels = read_labels(sphere)
    assert labels.source == "attribute polycube_label"
    assert np.array_equal(labels.values, expected)


def test_unrecognised_face_map_names_are_reported_by_name():
    sphere = uv_sphere()
    labels = nearest_axis_labels(sphere)
    add_face_maps(sphere, labels, ("+X", "Top", "+Y", "-Y", "+Z", "side"))
    before = vertices(sphere)
    message = deform_error(sphere)
    assert "'Top'" in message and "'side'" in message, message
    assert "POS_X" in message and "X+" in message and "NEG_X" in message, message
    assert message.count(".") == 1, message  # one sentence
    assert_untouched(sphere, before)


def test_an_empty_face_map_with_any_name_is_ignored():
    sphere = uv_sphere()
    add_face_maps(sphere, nearest_axis_labels(sphere), SPELLINGS["letters"])
    sphere.face_maps.new(name="Notes")
    assert deform(sphere, iterations=2) == {'FINISHED'}


def test_label_attribute_values_outside_minus_one_to_five_are_refused():
    sphere = uv_sphere()
    values = nearest_axis_labels(sphere).astype(np.int32)
    values[:3] = (7, -3, 7)
    add_attribute(sphere.data, "polycube_label", 'INT', values)
    before = vertices(sphere)
    message = deform_error(sphere)
    assert "polycube_label" in message and "-3, 7" in message and "3 faces" in message, message
    assert_untouched(sphere, before)


def test_label_attribute_of_the_wrong_kind_is_refused():
    sphere = uv_sphere()
    add_attribute(sphere.data, "polycube_label", 'FLOAT', np.zeros(len(sphere.data.polygons), np.float32))
    before = vertices(sphere)
    message = deform_error(sphere)
    assert "integer face attribute" in message, message
    assert_untouched(sphere, before)


def test_panel_summary_counts_faces_per_axis():
    sphere = uv_sphere()
    labels = nearest_axis_labels(sphere)
    labels[:10] = -1
    add_face_maps(sphere, labels, SPELLINGS["words"])
    summary = label_summary(sphere)
    assert summary.source == "face maps" and summary.error is None
    assert summary.counts == [int((labels == k).sum()) for k in range(6)]
    assert summary.unlabelled == 10
    sphere.face_maps[1].name = "junk"
    assert "'junk'" in label_summary(sphere).error
    sphere.face_maps[1].name = "NX"
    add_attribute(sphere.data, "polycube_label", 'INT', np.full(len(labels), 2, dtype=np.int32))
    assert label_summary(sphere).counts[2] == len(labels)
    sphere.data.attributes["polycube_label"].data[0].value = 3
    bpy.context.view_layer.update()  # the depsgraph update the UI would run
    assert label_summary(sphere).counts[2:4] == [len(labels) - 1, 1]


run_tests(globals())
