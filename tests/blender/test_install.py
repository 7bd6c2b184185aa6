"""The add-on as a user gets it: installed from the package zip, enabled, registered."""

import os
import sys
import zipfile

import addon_utils
import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import enable_addon, labelled_sphere, deform, report, run_tests  # noqa: E402

polycube = enable_addon()
INSTALLED = os.path.join(os.environ["BLENDER_USER_SCRIPTS"], "addons", "polycube")


def test_enabled_from_the_user_scripts_folder():
    assert os.path.dirname(polycube.__file__) == INSTALLED, polycube.__file__
    assert addon_utils.check("polycube") == (True, True)
    assert "polycube" in bpy.context.preferences.addons


def test_package_holds_what_the_zip_holds_and_no_stub():
    with zipfile.ZipFile(os.environ["POLYCUBE_ZIP"]) as archive:
        names = [name for name in archive.namelist() if not name.endswith("/")]
    assert all(name.startswith("polycube/") for name in names), names
    for name in names:
        assert os.path.isfile(os.path.join(os.path.dirname(INSTALLED), name)), name
    assert "polycube/blender_manifest.toml" in names
    assert "polycube/headless.py" in names
    assert "polycube/polycube_native.py" not in names
    assert any(name.startswith("polycube/polycube_native.") and name.endswith(".so") for name in names)


def test_native_module_is_the_compiled_one_inside_the_package():
    native = polycube.polycube_native
    assert native.__file__.endswith(".so"), native.__file__
    assert os.path.dirname(native.__file__) == INSTALLED
    assert native.LABEL_NAMES == ("+X", "-X", "+Y", "-Y", "+Z", "-Z")


def test_bl_info_and_manifest_agree():
    manifest = {}
    with open(os.path.join(INSTALLED, "blender_manifest.toml"), encoding="utf-8") as file:
        for line in file:
            if "=" in line:
                key, value = line.split("=", 1)
                manifest[key.strip()] = value.strip().strip('"')
    assert manifest["id"] == "polycube"
    assert manifest["type"] == "add-on"
    assert ".".join(map(str, polycube.bl_info["version"])) == manifest["version"]
    assert polycube.bl_info["blender"] == (3, 4, 0)


def test_everything_registered():
    assert hasattr(bpy.types, "OBJECT_OT_polycube_deform")
    assert hasattr(bpy.types, "VIEW3D_PT_polycube")
    assert bpy.types.VIEW3D_PT_polycube.bl_category == "Polycube"
    assert bpy.ops.object.polycube_deform.get_rna_type().name == "Deform to Polycube"
    assert {'REGISTER', 'UNDO'} <= set(bpy.types.OBJECT_OT_polycube_deform.bl_options)
    assert bpy.context.scene.polycube.iterations == 100
    assert bpy.context.preferences.addons["polycube"].preferences.live_preview is True


def test_disable_then_enable_again():
    handlers = len(bpy.app.handlers.depsgraph_update_post)
    bpy.ops.preferences.addon_disable(module="polycube")
    assert not hasattr(bpy.types, "OBJECT_OT_polycube_deform")
    assert not hasattr(bpy.types.Scene, "polycube")
    assert len(bpy.app.handlers.depsgraph_update_post) == handlers - 1
    enable_addon()
    sphere = labelled_sphere()
    assert deform(sphere, iterations=3) == {'FINISHED'}
    assert report(sphere)["iterations"] == 3


run_tests(globals())
