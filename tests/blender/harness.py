"""What the Blender test files share.

Each test_*.py runs inside Blender (run.py starts it), enables the add-on as a user
would, and ends with `run_tests(globals())`, which runs its test_* functions on a
clean scene and prints one `POLYCUBE-TEST PASS|FAIL <file>::<test>` line each.
"""

import os
import sys
import traceback

import bpy
import numpy as np

RESULT_PREFIX = "POLYCUBE-TEST"
ROOT = os.environ.get("POLYCUBE_ROOT", os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))))
MESHES = os.path.join(ROOT, "build", "data", "meshes")


def scratch_folder(name):
    """A folder for files a test writes; run.py removes them all at the end."""
    root = os.environ.get("POLYCUBE_TEST_TMP") or os.path.join(ROOT, "build", "test-tmp")
    folder = os.path.join(root, name)
    os.makedirs(folder, exist_ok=True)
    return folder


def enable_addon():
    """Enable the installed add-on through the preferences operator, as the UI does."""
    result = bpy.ops.preferences.addon_enable(module="polycube")
    assert result == {'FINISHED'}, result
    import polycube
    return polycube


def run_tests(namespace):
    """Run the test_* functions of a test file; exit code 1 if any failed."""
    script = os.path.basename(namespace["__file__"])
    wanted = os.environ.get("POLYCUBE_TEST_FILTER", "")
    failed = 0
    for name, test in list(namespace.items()):
        if not name.startswith("test_") or not callable(test) or wanted not in f"{script}::{name}":
            continue
        reset_scene()
        try:
            test()
        except Exception:
            traceback.print_exc()
            failed += 1
            print(f"{RESULT_PREFIX} FAIL {script}::{name}", flush=True)
        else:
            print(f"{RESULT_PREFIX} PASS {script}::{name}", flush=True)
    sys.stdout.flush()
    if failed:
        sys.exit(1)


def reset_scene():
    for data in (bpy.data.objects, bpy.data.meshes, bpy.data.actions, bpy.data.cameras,
                 bpy.data.lights, bpy.data.curves):
        for item in list(data):
            data.remove(item)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 250
    scene.frame_set(1)


# --- models -------------------------------------------------------------------

def uv_sphere(name="Sphere", segments=32, rings=16, location=(0, 0, 0)):
    bpy.ops.object.select_all(action='DESELECT')
    bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=rings, radius=1.0,
                                         location=location)
    obj = bpy.context.active_object
    obj.name = obj.data.name = name
    return obj


def cube_with_nine_faces_a_side():
    bpy.ops.mesh.primitive_cube_add()
    cube = bpy.context.active_object
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    bpy.ops.mesh.subdivide(number_cuts=2)
    bpy.ops.object.mode_set(mode='OBJECT')
    assert len(cube.data.polygons) == 54
    return cube


def nearest_axis_labels(obj):
    import polycube
    return np.asarray(polycube.polycube_native.nearest_labels(*arrays(obj)))


def add_face_maps(obj, labels, names):
    """Face maps (Blender 3.x) named names[label], holding the faces with that label."""
    for label, name in enumerate(names):
        faces = np.flatnonzero(np.asarray(labels) == label)
        if len(faces):
            obj.face_maps.new(name=name).add(faces.tolist())


def face_map_of_face(obj):
    """Each face's face map name, or None."""
    indices = np.full(len(obj.data.polygons), -1, dtype=np.int32)
    if len(obj.data.face_maps):
        obj.data.face_maps[0].data.foreach_get("value", indices)
    names = [face_map.name for face_map in obj.face_maps]
    return [names[i] if i >= 0 else None for i in indices]


def add_attribute(mesh, name, kind, values):
    attribute = mesh.attributes.new(name, kind, 'FACE')
    attribute.data.foreach_set("value", np.asarray(values))
    return attribute


def labelled_sphere(name="Sphere", **kwargs):
    obj = uv_sphere(name, **kwargs)
    add_face_maps(obj, nearest_axis_labels(obj), ("+X", "-X", "+Y", "-Y", "+Z", "-Z"))
    return obj


def off_object(path):
    import polycube
    vertices, face_indices, face_sizes = polycube.polycube_native.read_mesh(path)
    name = os.path.splitext(os.path.basename(path))[0]
    obj = bpy.data.objects.new(name, polycube.mesh_arrays.new_mesh(name, vertices, face_indices, face_sizes))
    bpy.context.scene.collection.objects.link(obj)
    return obj


# --- running and reading ------------------------------------------------------

def select_only(*objects):
    bpy.ops.object.select_all(action='DESELECT')
    for obj in objects:
        obj.select_set(True)
    bpy.context.view_layer.objects.active = objects[0]


def deform(*objects, **settings):
    if objects:
        select_only(*objects)
    return bpy.ops.object.polycube_deform(**settings)


def deform_error(*objects, **settings):
    """The message of the error the operator reports (it must report one)."""
    try:
        deform(*objects, **settings)
    except RuntimeError as error:
        return str(error)
    raise AssertionError("the operator reported no error")


def arrays(obj):
    import polycube
    return polycube.mesh_arrays.read_mesh_arrays(obj.data)


def vertices(obj):
    import polycube
    return polycube.mesh_arrays.read_coordinates(obj.data.vertices, len(obj.data.vertices))


def key_names(obj):
    key = obj.data.shape_keys
    return [block.name for block in key.key_blocks] if key is not None else []


def key_coordinates(obj, name):
    import polycube
    return polycube.shape_keys.read_key(obj.data.shape_keys.key_blocks[name])


def evaluated_coordinates(obj):
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    try:
        flat = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", flat)
        return flat.reshape(-1, 3).astype(np.float64)
    finally:
        evaluated.to_mesh_clear()


def report(obj):
    import polycube
    return polycube.report.load_report(obj)


def key_figures(obj, name, labels):
    """The quality figures (docs/design.md section 4) of a shape key, measured afresh."""
    import polycube
    mesh = arrays(obj)
    return polycube.polycube_native.figures(mesh.vertices, key_coordinates(obj, name),
                                            mesh.face_indices, mesh.face_sizes, labels)


def assert_untouched(obj, coordinates):
    """Nothing the operator writes is on the object, and its mesh is as it was."""
    assert obj.data.shape_keys is None, key_names(obj)
    assert "polycube_report" not in obj.keys()
    now = vertices(obj)
    assert np.array_equal(np.isnan(now), np.isnan(coordinates))
    assert np.array_equal(np.nan_to_num(now), np.nan_to_num(coordinates))
