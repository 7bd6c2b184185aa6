"""The add-on as a user gets it: installed from the package zip, enabled, registered."""

import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
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
    # Both name the README's section; the add-on made bl_info's a file:// address of its copy.
    assert manifest["website"] == "README.md#blender-add-on"
    assert polycube.help_links.resolve({"doc_url": manifest["website"]}, INSTALLED)["doc_url"] == \
        polycube.bl_info["doc_url"]


def test_documentation_and_bug_report_open_the_readme_inside_the_addon():
    readme = os.path.join(INSTALLED, "README.md")
    with open(readme, encoding="utf-8") as file:
        text = file.read()
    with open(os.path.join(os.environ["POLYCUBE_ROOT"], "README.md"), encoding="utf-8") as file:
        assert file.read() == text
    # The sections the addresses name exist (GitHub-style anchors of the headings).
    assert "\n## Blender add-on\n" in text and "\n### Reporting problems\n" in text
    # What the Preferences' buttons open: the add-on list's entry, as Blender 3.x makes it.
    listed = addon_utils.module_bl_info(
        next(module for module in addon_utils.modules(refresh=False) if module.__name__ == "polycube"))
    for info in (polycube.bl_info, listed):
        assert info["doc_url"] == f"file://{readme}#blender-add-on", info["doc_url"]
        assert info["tracker_url"] == f"file://{readme}#reporting-problems", info["tracker_url"]


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


# What every Linux that runs Blender has; the zip must carry every other library.
_SYSTEM = re.compile(r"^(linux-vdso|ld-linux|libc|libm|libstdc\+\+|libgcc_s|libgomp)[.\-]")


def test_the_zip_carries_every_library_beyond_glibc_and_libstdcxx():
    folder = tempfile.mkdtemp(prefix="polycube-unzipped-")
    try:
        with zipfile.ZipFile(os.environ["POLYCUBE_ZIP"]) as archive:
            archive.extractall(folder)
        unpacked = os.path.join(folder, "polycube")
        module, = glob.glob(os.path.join(unpacked, "polycube_native*.so"))
        plugin = os.path.join(unpacked, "polycube_cholmod.so")
        # CHOLMOD and its BLAS are the plugin's, loaded for large meshes only
        # (linear_algebra/supernodal_factor.h), not the module's.
        for binary, needs, lacks in ((module, "libosdCPU.so.3.5.0", "libcholmod.so.3"),
                                     (plugin, "libcholmod.so.3", "libosdCPU.so.3.5.0")):
            dynamic = subprocess.run(["readelf", "-d", binary], check=True, capture_output=True, text=True).stdout
            assert re.search(r"\(RPATH\)\s+Library rpath: \[\$ORIGIN/lib\]", dynamic), dynamic
            needed = re.findall(r"\(NEEDED\)\s+Shared library: \[(\S+)\]", dynamic)
            assert needs in needed and lacks not in needed, (binary, needed)
            # ldd resolves as the loader does (the zip's rpath, then the system).
            resolved = subprocess.run(["ldd", binary], check=True, capture_output=True, text=True).stdout
            outside = []
            for line in resolved.splitlines():
                name, _, where = line.strip().partition(" => ")
                assert "not found" not in where, line
                path = where.split(" (")[0]
                inside = os.path.realpath(path).startswith(os.path.realpath(unpacked) + os.sep)
                if where and not inside and not _SYSTEM.match(name):
                    outside.append(line.strip())
            assert not outside, (binary, outside)
        assert len(os.listdir(os.path.join(unpacked, "lib"))) >= 10
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def test_the_running_module_uses_the_libraries_inside_the_addon():
    # The plugin, and CHOLMOD with it, loads with the first large mesh, or here.
    assert polycube.polycube_native.supernodal_available()
    with open("/proc/self/maps", encoding="utf-8") as maps:
        mapped = {line.split()[-1] for line in maps if ".so" in line}
    # A library Blender itself loaded (Debian's Blender: OpenSubdiv) is shared by soname.
    blender_has = subprocess.run(["ldd", bpy.app.binary_path], capture_output=True, text=True).stdout
    bundled = os.listdir(os.path.join(INSTALLED, "lib"))
    for library in bundled:
        paths = [path for path in mapped if os.path.basename(path) == library]
        if library not in blender_has:
            assert paths == [os.path.join(INSTALLED, "lib", library)], (library, paths)
    assert "libcholmod.so.3" in bundled and "libcholmod.so.3" not in blender_has
    sphere = labelled_sphere()
    assert deform(sphere, iterations=50) == {'FINISHED'} and report(sphere)["converged"]


def test_a_module_that_cannot_load_leaves_the_addon_enabled_saying_why():
    scripts = tempfile.mkdtemp(prefix="polycube-broken-")
    try:
        broken = os.path.join(scripts, "addons", "polycube")
        shutil.copytree(INSTALLED, broken, ignore=shutil.ignore_patterns("lib", "__pycache__"))
        for module in glob.glob(os.path.join(broken, "polycube_native*.so")):
            with open(module, "wb") as file:
                file.write(b"not a shared library")
        script = (
            "import bpy, sys\n"
            "assert bpy.ops.preferences.addon_enable(module='polycube') == {'FINISHED'}\n"
            "import polycube\n"
            "assert hasattr(bpy.types, 'VIEW3D_PT_polycube_unavailable')\n"
            "assert not hasattr(bpy.types, 'OBJECT_OT_polycube_deform')\n"
            "print('REASON:', polycube.preferences.native_error())\n")
        done = subprocess.run(
            [bpy.app.binary_path, "-b", "--factory-startup", "--python-exit-code", "1", "--python-expr", script],
            env=dict(os.environ, BLENDER_USER_SCRIPTS=scripts), capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stdout + done.stderr
        assert re.search(r"REASON: .*polycube_native", done.stdout), done.stdout
    finally:
        shutil.rmtree(scripts, ignore_errors=True)


run_tests(globals())
