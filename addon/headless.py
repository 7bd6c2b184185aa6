# SPDX-License-Identifier: GPL-3.0-or-later
"""Deform to Polycube from the command line, in background Blender.

    blender -b --factory-startup --python <package>/headless.py -- \\
        --input model.off --iterations 200 --output out.blend --preview out.png

--input takes a .blend, a mesh file Blender imports (.obj, .ply, .stl) or an .off
file; without it a demo model is used (a UV sphere with face maps by nearest
axis). Labels come from the objects (docs/design.md section 3), from --labels FILE, a
text file with one label per face (-1..5), or with --labels auto from the
automatic labeller (written to the objects, as the Auto Label operator does).
--subdivide K deforms a subdivided copy `<name> polycube` of each object. --uv
gives every deformed object a UV map "Polycube" from its polycube, --remesh N an
all-quad object `<name> quads` of about N quads (the Polycube UV and Polycube
Remesh operators). The figures of each deformed object are printed; the exit
status is non-zero if any object could not be deformed or any output written, and
then no output is written.

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
    """The exit status: 0 when every object was deformed and every output written, 1 when
    not (and then no output is written), 2 for bad arguments or input, 3 for a bug."""
    try:
        return _run(argv)
    except Exception as error:  # noqa: BLE001 - a traceback alone would exit Blender with status 0
        import traceback
        traceback.print_exc()
        print(f"polycube: internal error: {error}", file=sys.stderr)
        return 3


def _run(argv):
    package = _load_package()
    args = _parse(argv, package.native_options)
    try:
        most = package.native_options.MAX_REFINE_LEVELS
        if not 0 <= args.subdivide <= most:
            raise ValueError(f"--subdivide must be 0..{most}, got {args.subdivide}")
        if args.remesh is not None and args.remesh < 6:
            raise ValueError(f"--remesh takes a number of quads of at least 6, got {args.remesh}")
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
            rerun_from_result=args.rerun_from_result, coarse_triangles=args.coarse_triangles, keep=args.keep.upper(), keep_every=args.keep_every, animate=args.animate,
            start_frame=args.start_frame, subdivide=args.subdivide > 0,
            subdivide_levels=max(args.subdivide, 1), subdivide_scheme=args.scheme.upper())
    except RuntimeError as error:
        # bpy turns the operators' error reports into this exception, "Error: ..." each.
        print(f"polycube: {str(error).strip().removeprefix('Error: ')}", file=sys.stderr)
        return 1

    # What was deformed is selected: the targets, or their subdivided copies.
    reports = {obj.name: package.report.load_report(obj) for obj in bpy.context.selected_objects
               if obj.type == 'MESH'}
    reports = {name: report for name, report in reports.items() if report is not None}
    try:
        for report in reports.values():
            _print_report(package, report)
        sys.stdout.flush()
    except OSError as error:  # the figures are a result too: > /dev/full is a failure
        print(f"polycube: cannot write to standard output: {error.strerror or error}; nothing written",
              file=sys.stderr)
        return 1
    if len(reports) != len(targets):
        print(f"polycube: {len(targets) - len(reports)} of {len(targets)} objects could not be deformed; "
              f"nothing written", file=sys.stderr)
        return 1
    try:
        _use_polycubes(args, reports)
    except RuntimeError as error:
        print(f"polycube: {str(error).strip().removeprefix('Error: ')}; nothing written", file=sys.stderr)
        return 1
    try:
        _write_outputs(args, reports, package)
    except (ValueError, OSError) as error:
        print(f"polycube: {error}", file=sys.stderr)
        return 1
    return 0


def _use_polycubes(args, reports):
    """--uv and --remesh on every deformed object, through the operators a user clicks
    (their messages, printed by Blender, give the figures); what each made goes into
    its report. The UV map comes first, so the quads carry it."""
    for name, report in reports.items():
        obj = bpy.data.objects[name]
        bpy.context.view_layer.objects.active = obj
        if args.uv:
            bpy.ops.object.polycube_uv(relax=args.uv != "polycube", merge=args.uv == "merged")
            report["uv"] = {"map": obj.data.uv_layers.active.name, "kind": args.uv}
        if args.remesh:
            bpy.ops.object.polycube_remesh(mode='FACES', target_faces=args.remesh)
            quads = bpy.context.active_object
            report["remesh"] = {"object": quads.name, "faces": len(quads.data.polygons),
                                "vertices": len(quads.data.vertices)}


def _write_outputs(args, reports, package):
    """The .blend, the report and the preview, all or none (output_files.py)."""
    written = []
    with package.output_files.OutputFiles() as outputs:
        if args.output:
            temporary = outputs.temporary(args.output)
            os.remove(temporary)  # over an existing file Blender would keep the empty one as .blend1
            try:
                bpy.ops.wm.save_as_mainfile(filepath=temporary, check_existing=False, copy=True)
            except RuntimeError as error:
                raise ValueError(f"cannot write {args.output}: {str(error).strip()}") from None
            written.append(args.output)
        if args.report:
            with open(outputs.temporary(args.report), "w", encoding="utf-8") as file:
                json.dump(reports, file, indent=2)
            written.append(args.report)
        if args.preview:
            temporary = outputs.temporary(args.preview, suffix=".png")  # the render adds .png otherwise
            package.preview.render_preview([bpy.data.objects[name] for name in reports], temporary)
            if os.path.getsize(temporary) == 0:  # the render reports a failed write but does not raise
                raise ValueError(f"cannot write {args.preview}: the preview render was not saved")
            written.append(args.preview)
        sys.stdout.flush()
        outputs.commit()
    for path in written:
        print(f"Wrote {path}")


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
    parser.add_argument("--rerun-from-result", action="store_true",
                        help="robust, 100,000 triangles and more: the further runs that relabel collapsed "
                             "faces start from the result instead of the input (several times faster)")
    parser.add_argument("--coarse-triangles", type=int, default=native_options.DEFAULT_COARSE_TRIANGLES,
                        metavar="N",
                        help="robust: a mesh of at least 4 N triangles whose labels do not flatten without help "
                             "is deformed through a copy decimated to about N (0: always the mesh itself)")
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
    parser.add_argument("--uv", choices=("polycube", "conformal", "merged"),
                        help="a UV map 'Polycube' on every deformed object, one island per chart: the "
                             "polycube's own positions, conformal in the same islands, or conformal with "
                             "neighbouring islands merged")
    parser.add_argument("--remesh", type=int, metavar="FACES",
                        help="an all-quad object '<name> quads' of about FACES quads from every polycube")
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
    for submodule in ("report", "preview", "labels", "mesh_arrays", "native_options", "output_files",
                      "polycube_native"):
        importlib.import_module(f"{name}.{submodule}")
    return sys.modules[name]


def _load_input(args, package):
    if args.input is None:
        _remove_all_objects()
        targets = [_demo_sphere(package)]
    else:
        path = os.path.abspath(args.input)
        if os.path.isdir(path):
            raise ValueError(f"{args.input} is a directory; --input takes a .blend, .obj, .ply, .stl or .off file")
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
            if extension in (".obj", ".ply"):
                # Blender's importers take what they can from a truncated or broken file;
                # the native reader (the command-line program's) refuses it with the line at fault.
                package.polycube_native.read_mesh(path)
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
    # The native reader, as the command-line program's --labels FILE: integers -1..5 only.
    values = package.polycube_native.read_labels(path, len(targets[0].data.polygons))
    package.labels.write_label_attribute(targets[0].data, values)


def _print_report(package, report):
    seconds = report["seconds"]
    print(f"{report['object']}: {report['iterations']} iterations, {package.report.outcome(report)}; "
          f"{report['vertices']} vertices, {report['faces']} faces, labels from {report['label_source']}")
    print(f"  normal deviation  max {report['normal_deviation_max_deg']:.4f}°  "
          f"mean {report['normal_deviation_mean_deg']:.4f}°")
    print(f"  flipped faces {report['flipped_faces']}  collapsed faces {report['collapsed_faces']}  "
          f"unlabelled faces {report['unlabelled_faces']}")
    print(f"  edge error {report['edge_error']:.4f}  area error {report['area_error']:.4f}  "
          f"largest area ratio {report.get('max_area_ratio', 0.0):.1f}")
    print(f"  shape keys {len(report['kept_iterations'])}  "
          f"seconds: read {seconds['read']:.3f}  solve {seconds['deform_call']:.3f}  "
          f"write {seconds['write']:.3f}")
    for line in package.report.advice(report):
        print(f"  {line}")


if __name__ == "__main__":
    sys.exit(main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []))
