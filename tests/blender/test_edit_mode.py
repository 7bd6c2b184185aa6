"""Labels where users edit them: read in Edit Mode (through bmesh), Assign Label on
the selected faces (colors, undo), the menus F3 searches, Select Unconverged Faces
selecting every such face, Validate keeping the other objects selected."""

import os
import sys

import bmesh
import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import (  # noqa: E402
    add_attribute, add_face_maps, cube_with_nine_faces_a_side, deform, enable_addon, face_map_of_face,
    nearest_axis_labels, report, run_tests, select_only, uv_sphere)

polycube = enable_addon()
from polycube.label_cache import label_summary  # noqa: E402
from polycube.label_colours import LABEL_COLOURS, NEAREST_COLOURS  # noqa: E402
from polycube.labels import read_labels, write_face_maps, write_label_attribute  # noqa: E402

NAMES = polycube.polycube_native.LABEL_NAMES


def _labels_attribute(obj):
    values = np.empty(len(obj.data.polygons), dtype=np.int32)
    obj.data.attributes["polycube_label"].data.foreach_get("value", values)
    return values


def _face_colours(obj):
    """The label color attribute per face (its first corner), linear RGBA."""
    attribute = obj.data.color_attributes["polycube_label_colour"]
    corners = np.empty(len(obj.data.loops) * 4, dtype=np.float32)
    attribute.data.foreach_get("color", corners)
    starts = np.empty(len(obj.data.polygons), dtype=np.int32)
    obj.data.polygons.foreach_get("loop_start", starts)
    return corners.reshape(-1, 4)[starts]


def _select_faces_in_edit_mode(obj, faces):
    bpy.context.tool_settings.mesh_select_mode = (False, False, True)
    bpy.ops.mesh.select_all(action='DESELECT')
    bm = bmesh.from_edit_mesh(obj.data)
    bm.faces.ensure_lookup_table()
    for f in faces:
        bm.faces[f].select_set(True)
    bmesh.update_edit_mesh(obj.data)
    assert [face.index for face in bm.faces if face.select] == sorted(faces)


def _face_map_labels(obj):
    """The label each face's face map names (-1: in none)."""
    return np.array([NAMES.index(name) if name is not None else -1 for name in face_map_of_face(obj)])


def _selected_faces(obj):
    flags = np.empty(len(obj.data.polygons), dtype=bool)
    obj.data.polygons.foreach_get("select", flags)
    return np.flatnonzero(flags)


def test_every_label_store_reads_the_same_in_edit_mode():
    for store in ("attribute", "face maps"):
        sphere = uv_sphere(f"Sphere {store}")
        labels = nearest_axis_labels(sphere)
        if store == "attribute":
            add_attribute(sphere.data, "polycube_label", 'INT', labels.astype(np.int32))
        else:
            add_face_maps(sphere, labels, NAMES)
        select_only(sphere)
        bpy.ops.object.mode_set(mode='EDIT')
        try:
            edited = read_labels(sphere)
            summary = label_summary(sphere)
        finally:
            bpy.ops.object.mode_set(mode='OBJECT')
        assert edited.values.tolist() == labels.tolist(), store
        assert summary.error is None and summary.counts == np.bincount(labels, minlength=6).tolist(), summary


def test_labels_of_faces_added_in_edit_mode_are_counted_without_leaving_it():
    bpy.ops.mesh.primitive_cube_add()
    cube = bpy.context.active_object
    add_attribute(cube.data, "polycube_label", 'INT', nearest_axis_labels(cube).astype(np.int32))
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    bpy.ops.mesh.subdivide(number_cuts=1)  # 6 faces -> 24, each child keeps its parent's label
    summary = label_summary(cube)
    bpy.ops.object.mode_set(mode='OBJECT')
    assert summary.error is None and summary.counts == [4] * 6, summary


def test_assign_label_in_edit_mode_colors_and_undo():
    sphere = uv_sphere()
    labels = nearest_axis_labels(sphere)
    add_face_maps(sphere, labels, NAMES)  # labels in face maps only: the attribute is made on assigning
    select_only(sphere)
    assert bpy.ops.object.polycube_label_colours(show=True) == {'FINISHED'}
    bpy.ops.object.mode_set(mode='EDIT')
    chosen = [0, 1, 2, 40, 41, 300]
    _select_faces_in_edit_mode(sphere, chosen)
    bpy.ops.ed.undo_push(message="faces selected")
    assert bpy.ops.mesh.polycube_assign_label(label='-Z') == {'FINISHED'}
    bpy.ops.ed.undo_push(message="Assign Label")
    summary = label_summary(sphere)
    expected_count = np.count_nonzero(labels == 5) + np.count_nonzero(labels[chosen] != 5)
    assert summary.counts[5] == expected_count, (summary, expected_count, labels[chosen])
    bpy.ops.object.mode_set(mode='OBJECT')
    expected = labels.copy()
    expected[chosen] = 5
    assert _labels_attribute(sphere).tolist() == expected.tolist()
    colours = _face_colours(sphere)
    # Byte colors round to 1/255 in sRGB.
    assert np.abs(colours[chosen] - LABEL_COLOURS[5]).max() < 0.01
    assert np.abs(colours - LABEL_COLOURS[expected]).max() < 0.01
    # Blender 3.x: the face maps moved with the attribute.
    assert _face_map_labels(sphere).tolist() == expected.tolist()

    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.ed.undo()
    bpy.ops.object.mode_set(mode='OBJECT')
    sphere = bpy.data.objects["Sphere"]
    assert "polycube_label" not in sphere.data.attributes
    assert read_labels(sphere).values.tolist() == labels.tolist()
    assert _face_map_labels(sphere).tolist() == labels.tolist()

    select_only(sphere)
    bpy.ops.object.mode_set(mode='EDIT')
    _select_faces_in_edit_mode(sphere, [7])
    assert bpy.ops.mesh.polycube_assign_label(label='NONE') == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    values = _labels_attribute(sphere)
    assert values[7] == -1 and np.array_equal(np.delete(values, 7), np.delete(labels, 7))
    assert _face_map_labels(sphere).tolist() == values.tolist()
    # A cleared face shows the axis the solver gives it, pale.
    assert np.abs(_face_colours(sphere)[7] - NEAREST_COLOURS[labels[7]]).max() < 0.01


def test_assign_label_keeps_our_face_maps_and_leaves_the_users():
    bpy.ops.mesh.primitive_cube_add()
    cube = bpy.context.active_object
    labels = nearest_axis_labels(cube)  # one face a label
    write_label_attribute(cube.data, labels)
    write_face_maps(cube, labels)
    notes = int(np.flatnonzero(labels == 2)[0])  # the +Y face goes into a map of the user's
    cube.face_maps.new(name="Notes").add([notes])
    select_only(cube)
    bpy.ops.object.mode_set(mode='EDIT')
    plus_x, minus_x = (int(np.flatnonzero(labels == label)[0]) for label in (0, 1))
    _select_faces_in_edit_mode(cube, [plus_x, notes])
    assert bpy.ops.mesh.polycube_assign_label(label='-X') == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    expected = labels.copy()
    expected[[plus_x, notes]] = 1
    assert _labels_attribute(cube).tolist() == expected.tolist()
    maps = face_map_of_face(cube)
    assert maps[notes] == "Notes" and maps[plus_x] == maps[minus_x] == "-X", maps
    # The +X map lost its only face: gone, as Auto Label leaves no empty map of ours.
    assert sorted(face_map.name for face_map in cube.face_maps) == sorted(["-X", "+Z", "-Y", "-Z", "Notes"])


def test_assign_label_needs_edit_mode_and_a_selection():
    sphere = uv_sphere()
    select_only(sphere)
    assert not bpy.ops.mesh.polycube_assign_label.poll()
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='DESELECT')
    try:
        bpy.ops.mesh.polycube_assign_label(label='+X')
    except RuntimeError as error:
        assert "Select the faces" in str(error) or "CANCELLED" in str(error), error
    bpy.ops.object.mode_set(mode='OBJECT')
    assert "polycube_label" not in sphere.data.attributes


class _Recorder:
    """Stands in for a UILayout: records the operators and menus a draw function adds."""

    def __init__(self, found):
        self.found = found

    def operator(self, idname, **_kwargs):
        self.found.add(idname)
        return _Properties(self.found)

    def menu(self, idname, **_kwargs):
        self.found.add(idname)
        getattr(bpy.types, idname).draw(_Holder(self), bpy.context)

    def __getattr__(self, _name):
        return lambda *args, **kwargs: self


class _Properties:
    def __init__(self, found):
        self.__dict__["found"] = found

    def __setattr__(self, name, value):
        if name == "name":  # wm.call_menu_pie(name=...): the pie's own entries
            self.found.add(value)
            getattr(bpy.types, value).draw(_Holder(_Recorder(self.found)), bpy.context)


class _Holder:
    def __init__(self, layout):
        self.layout = layout


def _menu_entries(menu):
    found = set()
    for draw in getattr(bpy.types, menu)._dyn_ui_initialize():
        if draw.__module__.startswith("polycube"):
            draw(_Holder(_Recorder(found)), bpy.context)
    return found


def test_every_operator_is_in_a_menu_and_the_pie_has_a_key():
    operators = {f"{cls.bl_idname}" for cls in bpy.types.Operator.__subclasses__()
                 if cls.__module__.startswith("polycube")}
    assert len(operators) >= 6, operators
    in_object_menu = _menu_entries("VIEW3D_MT_object")
    in_face_menu = _menu_entries("VIEW3D_MT_edit_mesh_faces")
    in_context_menu = _menu_entries("VIEW3D_MT_edit_mesh_context_menu")
    assert operators - {"mesh.polycube_assign_label"} <= in_object_menu, operators - in_object_menu
    for found in (in_face_menu, in_context_menu):
        assert {"mesh.polycube_assign_label", "object.polycube_validate_labels",
                "VIEW3D_MT_polycube_label_pie"} <= found, found
    # The default shortcut, as documented: Shift Alt L in the Mesh (Edit Mode) keymap.
    assert polycube.menus.PIE_KEY == dict(type='L', value='PRESS', shift=True, alt=True)


def test_select_unconverged_selects_every_face_past_a_thousand():
    sphere = uv_sphere(segments=128, rings=64)
    add_attribute(sphere.data, "polycube_label", 'INT', np.full(len(sphere.data.polygons), 4, np.int32))
    deform(sphere, iterations=2, tolerance=0.01, variant='FIXED')
    count = report(sphere)["unconverged_faces_count"]
    assert count > 1000, count
    select_only(sphere)
    bpy.ops.object.mode_set(mode='EDIT')  # from Edit Mode, as a user looking at faces would
    assert bpy.ops.object.polycube_select_unconverged() == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    assert len(_selected_faces(sphere)) == count


def test_validate_keeps_the_other_objects_selected():
    other = uv_sphere("Other", location=(3, 0, 0))
    cube = cube_with_nine_faces_a_side()
    labels = nearest_axis_labels(cube)
    labels[0] = labels[0] ^ 1  # one face beside its opposite label (0 <-> 1, 2 <-> 3, 4 <-> 5)
    add_attribute(cube.data, "polycube_label", 'INT', labels.astype(np.int32))
    select_only(cube, other)
    assert bpy.ops.object.polycube_validate_labels() == {'FINISHED'}
    assert cube.mode == 'EDIT' and other.mode == 'OBJECT'
    assert other.select_get() and cube.select_get()
    bpy.ops.object.mode_set(mode='OBJECT')


run_tests(globals())
