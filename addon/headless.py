# SPDX-License-Identifier: GPL-3.0-or-later
"""Deform to Polycube from the command line, in background Blender.

    blender -b --factory-startup --python <package>/headless.py -- \\
        --input model.off --iterations 200 --output out.blend --preview out.png

--input takes a .blend, a mesh file Blender imports (.obj, .ply, .stl) or an .off
file; without it a demo model is used (a UV sphere with face maps by nearest
axis). Labels come from the objects (DESIGN.md section 3), from --labels FILE, a
text file with one label per face (-1..5), or with --labels auto from the
automatic labeller (written to the objects, as the Auto Label operator does).
--subdivide K deforms a subdivided copy `<name> polycube` of each object. The
figures of each deformed object are printed; the exit status is non-zero if any
object could not be deformed.

Labels are axes of each object's own (local) coordinates; mesh files are imported
without axis conversion so they keep the coordinates written in the file.
"""

import argparse
import importlib
import importlib.util
import json
import os
import sys

import bpy

_IMPORTERS = {  # newest operator first; later ones serve older Blender versions
    ".obj": (("wm", "obj_import", dict(forward_axis='Y', up_axis='Z')),
             ("import_scene", "obj", dict(axis_forward='Y', axis_up='Z'))),
    ".ply": (("wm", "ply_import", dict(forward_axis='Y', up_axis='Z')),
             ("import_mesh", "ply", {})),
    ".stl": (("wm", "stl_import", dict(forward_axis='Y', up_axis='Z')),
             ("import_mesh", "stl", dict(axis_forward='Y', axis_up='Z'))),
}


def main(argv):
    package = _load_package()
    args = _parse(argv, package.native_options)
    try:
        targets = _load_input(args, package)
        if args.labels and args.labels != "auto":
            _apply_label_file(args.labels, targets, package)
    except ValueError as error:
        print(f"polycube: {error}", file=sys.stderr)
        return 2

    bpy.ops.object.select_all(action='DESELECT')
    for obj in targets:
        obj.select_set(True)
    bpy.context.view_layer.objects.active = targets[0]
    try:
        if args.labels == "auto":
            bpy.ops.object.polycube_auto_label(detail=args.detail)
        bpy.ops.object.polycube_deform(
            iterations=args.iterations, tolerance=args.tolerance, variant=args.variant.upper(),
            keep=args.keep.upper(), keep_every=args.keep_every, animate=args.animate,
            start_frame=args.start_frame, subdivide=args.subdivide > 0,
            subdivide_levels=max(args.subdivide, 1), subdivide_scheme=args.scheme.upper())
    except RuntimeError as error:
        # bpy turns the operator's error reports into this exception, "Error: ..." each.
        print(f"polycube: {str(error).strip().removeprefix('Error: ')}", file=sys.stderr)
        return 1

    # What was deformed is selected: the targets, or their subdivided copies.
    reports = {obj.name: package.report.load_report(obj) for obj in bpy.context.selected_objects
               if obj.type == 'MESH'}
    reports = {name: report for name, report in reports.items() if report is not None}
    for report in reports.values():
        _print_report(package, report)
    if args.output:
        _ensure_folder(args.output)
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.output), check_existing=False)
        print(f"Wrote {args.output}")
    if args.report:
        _ensure_folder(args.report)
        with open(args.report, "w", encoding="utf-8") as file:
            json.dump(reports, file, indent=2)
        print(f"Wrote {args.report}")
    if args.preview and reports:
        _ensure_folder(args.preview)
        package.preview.render_preview([bpy.data.objects[name] for name in reports],
                                       os.path.abspath(args.preview))
        print(f"Wrote {args.preview}")
    return 0 if len(reports) == len(targets) else 1


def _parse(argv, native_options):
    parser = argparse.ArgumentParser(
        prog="blender -b --factory-startup --python headless.py --",
        description="Deform mesh objects into their polycube, a shape key per iteration.")
    parser.add_argument("--input", help=".blend, .obj, .ply, .stl or .off (default: a demo sphere)")
    parser.add_argument("--objects", nargs="+", metavar="NAME",
                        help="objects to deform (default: every mesh object of the input)")
    parser.add_argument("--labels", metavar="FILE|auto",
                        help="a file with one label per face (-1..5 = none, +X, -X, +Y, -Y, +Z, -Z; "
                             "one object only), or auto: the automatic labeller on every object")
    parser.add_argument("--detail", type=float, default=native_options.DEFAULT_DETAIL,
                        help="automatic labels, 0..1: 0 gives a few large charts, 1 many small ones")
    parser.add_argument("--iterations", type=int, default=100)
    parser.add_argument("--tolerance", type=float, default=0.5,
                        help="degrees (0: run every iteration)")
    parser.add_argument("--variant", choices=native_options.VARIANTS, default=native_options.DEFAULT_VARIANT)
    parser.add_argument("--keep", choices=("all", "every", "final"), default="all",
                        help="which iterations become shape keys")
    parser.add_argument("--keep-every", type=int, default=5, metavar="K")
    parser.add_argument("--animate", action="store_true",
                        help="keyframe the shape keys: frame start + k shows iteration k")
    parser.add_argument("--start-frame", type=int, default=1)
    parser.add_argument("--subdivide", type=int, default=0, metavar="K",
                        help="deform a copy '<name> polycube' subdivided K times (0: the object itself)")
    parser.add_argument("--scheme", choices=("bilinear", "loop", "catmark"), default="bilinear",
                        help="subdivision scheme")
    parser.add_argument("--output", metavar="FILE.blend", help="where to save the result")
    parser.add_argument("--preview", metavar="FILE.png",
                        help="Workbench render of the input beside the polycube")
    parser.add_argument("--report", metavar="FILE.json", help="the figures of every object")
    return parser.parse_args(argv)


def _load_package():
    """This script's add-on package, registered unless an enabled add-on already is."""
    operator = getattr(bpy.types, "OBJECT_OT_polycube_deform", None)
    if operator is not None:
        name = operator.__module__.rsplit(".", 1)[0]
    else:
        here = os.path.dirname(os.path.abspath(__file__))
        name = "polycube"
        spec = importlib.util.spec_from_file_location(
            name, os.path.join(here, "__init__.py"), submodule_search_locations=[here])
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
        module.register()
    for submodule in ("report", "preview", "labels", "mesh_arrays", "native_options", "polycube_native"):
        importlib.import_module(f"{name}.{submodule}")
    return sys.modules[name]


def _load_input(args, package):
    if args.input is None:
        _remove_all_objects()
        targets = [_demo_sphere(package)]
    else:
        path = os.path.abspath(args.input)
        if not os.path.isfile(path):
            raise ValueError(f"no such file: {args.input}")
        extension = os.path.splitext(path)[1].lower()
        if extension == ".blend":
            bpy.ops.wm.open_mainfile(filepath=path)
            targets = [obj for obj in bpy.context.scene.objects if obj.type == 'MESH']
        elif extension == ".off":
            _remove_all_objects()
            vertices, face_indices, face_sizes = package.polycube_native.read_mesh(path)
            name = os.path.splitext(os.path.basename(path))[0]
            mesh = package.mesh_arrays.new_mesh(name, vertices, face_indices, face_sizes)
            obj = bpy.data.objects.new(name, mesh)
            bpy.context.scene.collection.objects.link(obj)
            targets = [obj]
        elif extension in _IMPORTERS:
            _remove_all_objects()
            _import(path, extension)
            targets = [obj for obj in bpy.context.scene.objects if obj.type == 'MESH']
        else:
            raise ValueError(f"cannot read {extension} files; use .blend, .obj, .ply, .stl or .off")
    if args.objects:
        missing = [name for name in args.objects if name not in bpy.context.scene.objects]
        if missing:
            available = ", ".join(sorted(obj.name for obj in bpy.context.scene.objects))
            raise ValueError(f"no object named {', '.join(missing)} (the scene has: {available})")
        targets = [bpy.context.scene.objects[name] for name in args.objects]
    if not targets:
        raise ValueError(f"{args.input} holds no mesh object")
    return targets


def _import(path, extension):
    for module, name, options in _IMPORTERS[extension]:
        operator = getattr(getattr(bpy.ops, module), name)
        try:
            operator.get_rna_type()
        except KeyError:
            continue  # not in this Blender version
        operator(filepath=path, **options)
        return
    raise ValueError(f"this Blender has no importer for {extension} files")


def _remove_all_objects():
    # The factory startup scene's cube, camera and light do not belong in the output.
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)


def _demo_sphere(package):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=1.0)
    obj = bpy.context.active_object
    labels = package.polycube_native.nearest_labels(*package.mesh_arrays.read_mesh_arrays(obj.data))
    if hasattr(obj, "face_maps"):
        package.labels.write_face_maps(obj, labels)
    else:
        package.labels.write_label_attribute(obj.data, labels)
    return obj


def _apply_label_file(path, targets, package):
    if len(targets) != 1:
        raise ValueError("--labels needs exactly one object; choose it with --objects")
    import numpy as np
    try:
        values = np.loadtxt(path, dtype=np.int64, ndmin=1)
    except ValueError:
        raise ValueError(f"{path} must hold one integer label per line") from None
    faces = len(targets[0].data.polygons)
    if len(values) != faces:
        raise ValueError(f"{path} has {len(values)} labels but '{targets[0].name}' has {faces} faces")
    package.labels.write_label_attribute(targets[0].data, values)


def _print_report(package, report):
    seconds = report["seconds"]
    print(f"{report['object']}: {report['iterations']} iterations, {package.report.outcome(report)}; "
          f"{report['vertices']} vertices, {report['faces']} faces, labels from {report['label_source']}")
    print(f"  normal deviation  max {report['normal_deviation_max_deg']:.4f}°  "
          f"mean {report['normal_deviation_mean_deg']:.4f}°")
    print(f"  flipped faces {report['flipped_faces']}  collapsed faces {report['collapsed_faces']}  "
          f"unlabelled faces {report['unlabelled_faces']}")
    print(f"  edge error {report['edge_error']:.4f}  area error {report['area_error']:.4f}")
    print(f"  shape keys {len(report['kept_iterations'])}  "
          f"seconds: read {seconds['read']:.3f}  solve {seconds['deform_call']:.3f}  "
          f"write {seconds['write']:.3f}")
    for line in package.report.advice(report):
        print(f"  {line}")


def _ensure_folder(path):
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)


if __name__ == "__main__":
    sys.exit(main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []))
