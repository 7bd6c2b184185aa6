// The Python face of the core: numpy arrays in and out, options as keyword
// arguments, the GIL released while computing, every failure a ValueError
// (bad input) or RuntimeError (a solve that broke down) with one clear sentence.
//
// Conversions are strict: an index or label array must hold integers (any
// integer dtype) that fit, or the call raises TypeError / ValueError naming
// the argument. Casting would turn index 2**32 + 1 into 1, or label 2.7 into
// 2, and the call would then succeed on a mesh the caller never gave.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <climits>
#include <cstring>
#include <type_traits>

#include "deform/deform.h"
#include "deform/quality.h"
#include "io/deform_report.h"
#include "io/labels_io.h"
#include "io/labels_report.h"
#include "io/read_mesh.h"
#include "labeller/auto_labels.h"
#include "labels/axis.h"
#include "labels/nearest_labels.h"
#include "labels/orientation.h"
#include "labels/validate_labels.h"
#include "linear_algebra/supernodal_factor.h"
#include "mesh/check_input.h"
#include "mesh/triangulate.h"
#include "mesh/unit_box.h"
#include "refine/refine.h"
#include "use/polycube_uv.h"
#include "use/quad_remesh.h"
#include "use/uv_figures.h"

namespace py = pybind11;
using namespace polycube;

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
// Any array-like; checked and converted by to_ints.
using IntArray = py::object;

Vertices to_vertices(const DoubleArray& array, const char* name) {
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw py::value_error(std::string(name) + " must be an (n, 3) array, got shape " +
                          std::string(py::str(py::tuple(
                              py::cast(std::vector<py::ssize_t>(array.shape(), array.shape() + array.ndim()))))));
  Vertices v(array.shape(0), 3);
  if (array.size() > 0) std::memcpy(v.data(), array.data(), sizeof(double) * array.size());
  return v;
}

// The values of a 1-D integer array, each within [low, high]; what is
// allowed is said in `meaning` ("vertex indices 0..41").
template <class T>
std::vector<int> checked_ints(const py::array& array, const char* name, long long low, long long high,
                              const std::string& meaning) {
  const auto values = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
  std::vector<int> out(values.size());
  for (py::ssize_t k = 0; k < values.size(); ++k) {
    const T value = values.data()[k];
    bool outside;
    if constexpr (std::is_signed_v<T>)
      outside = value < low || value > high;
    else  // compared unsigned: a uint64 above 2**63 must not wrap to a negative
      outside = high < 0 || value > static_cast<unsigned long long>(high) ||
                (low > 0 && value < static_cast<unsigned long long>(low));
    if (outside)
      throw py::value_error(std::string(name) + "[" + std::to_string(k) + "] is " + std::to_string(value) +
                            ", outside " + meaning);
    out[k] = static_cast<int>(value);
  }
  return out;
}

std::vector<int> to_ints(const IntArray& object, const char* name, long long low = INT_MIN, long long high = INT_MAX,
                         const std::string& meaning = "the int32 range") {
  const py::array array = py::array::ensure(object);
  if (!array) throw py::type_error(std::string(name) + " must be an array of integers");
  if (array.ndim() != 1) throw py::value_error(std::string(name) + " must be a flat (1-D) array");
  if (array.size() == 0) return {};  // np.asarray([]) is float64: nothing to convert
  const char kind = array.dtype().kind();
  if (kind == 'i') return checked_ints<long long>(array, name, low, high, meaning);
  if (kind == 'u') return checked_ints<unsigned long long>(array, name, low, high, meaning);
  throw py::type_error(std::string(name) + " must hold integers, got dtype " + std::string(py::str(array.dtype())) +
                       (kind == 'f' ? " (convert deliberately, e.g. np.rint(a).astype(np.int32))" : ""));
}

std::vector<int> to_labels(const IntArray& object, const char* name = "labels") {
  return to_ints(object, name, -1, 5, "-1..5 (0..5 = +X, -X, +Y, -Y, +Z, -Z, -1 = unlabelled)");
}

PolygonMesh to_mesh(const DoubleArray& vertices, const IntArray& face_indices, const IntArray& face_sizes) {
  PolygonMesh mesh;
  mesh.vertices = to_vertices(vertices, "vertices");
  const long long n = mesh.vertices.rows();
  const std::string vertex_range =
      n > 0 ? "the vertex indices 0.." + std::to_string(n - 1) : std::string("any vertex index: there are no vertices");
  mesh.faces.indices = to_ints(face_indices, "face_indices", 0, n - 1, vertex_range);
  const std::vector<int> sizes =
      to_ints(face_sizes, "face_sizes", 3, INT_MAX, "3.. (every face needs at least 3 corners)");
  mesh.faces.offsets.resize(sizes.size() + 1);
  long total = 0;
  for (size_t f = 0; f < sizes.size(); ++f) {
    if (sizes[f] < 3)
      throw py::value_error("face " + std::to_string(f) + " has " + std::to_string(sizes[f]) +
                            " corners; every face needs at least 3");
    total += sizes[f];
    if (total > static_cast<long>(mesh.faces.indices.size())) break;
    mesh.faces.offsets[f + 1] = static_cast<int>(total);
  }
  if (total != static_cast<long>(mesh.faces.indices.size()))
    throw py::value_error("face_sizes add up to " + std::to_string(total) + " corners, but face_indices has " +
                          std::to_string(mesh.faces.indices.size()));
  return mesh;
}

py::array_t<double> to_numpy(const Vertices& v) {
  py::array_t<double> out({static_cast<py::ssize_t>(v.rows()), py::ssize_t{3}});
  if (v.size() > 0) std::memcpy(out.mutable_data(), v.data(), sizeof(double) * v.size());
  return out;
}

py::array_t<int> to_int_array(const std::vector<int>& v) {
  return py::array_t<int>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::object json_loads(const Json& json) { return py::module_::import("json").attr("loads")(json_text(json, -1)); }

py::dict figures_dict(const Figures& figures) {
  Json json = Json::object();
  add_figures(json, figures);
  return json_loads(json);
}

py::dict deform_py(const DoubleArray& vertices, const IntArray& face_indices, const IntArray& face_sizes,
                   const IntArray& labels, int iterations, double tolerance, const std::string& variant,
                   bool relabel_collapsed, bool rerun_from_result, bool last_resort, bool polish,
                   int coarse_triangles, const std::optional<py::function>& callback, const std::optional<py::function>& stop) {
  PolygonMesh mesh = to_mesh(vertices, face_indices, face_sizes);
  const std::vector<int> face_labels = to_labels(labels);
  DeformOptions options;
  options.iterations = iterations;
  options.tolerance_deg = tolerance;
  options.variant = parse_variant(variant);
  options.relabel_collapsed = relabel_collapsed;
  options.rerun_from_result = rerun_from_result;
  options.last_resort = last_resort;
  options.polish = polish;
  if (coarse_triangles < 0) throw Error("coarse_triangles must be 0 (off) or more");
  options.coarse_triangles = coarse_triangles;

  if (stop)
    options.stop_requested = [&stop]() {
      py::gil_scoped_acquire gil;
      return py::cast<bool>(py::bool_((*stop)()));
    };
  IterationCallback on_iteration;
  if (callback) {
    on_iteration = [&callback](int iteration, const Vertices& positions, const Figures& figures) {
      py::gil_scoped_acquire gil;
      py::dict f = figures_dict(figures);
      f["iteration"] = iteration;
      const py::object answer = (*callback)(iteration, to_numpy(positions), f);
      if (answer.is_none()) return true;
      if (py::isinstance<py::bool_>(answer) || py::isinstance(answer, py::module_::import("numpy").attr("bool_")))
        return py::cast<bool>(py::bool_(answer));
      throw py::type_error("callback must return True (go on), False (stop) or None, got " +
                           std::string(py::str(py::type::of(answer).attr("__name__"))));
    };
  }
  DeformResult result;
  {
    py::gil_scoped_release release;
    result = deform(mesh, face_labels, options, on_iteration);
  }
  py::dict out;
  out["positions"] = to_numpy(result.positions);
  out["labels"] = to_int_array(result.labels);
  py::dict report = json_loads(deform_report(mesh, result, options));
  // The JSON report lists at most a thousand ids per face list (a file for people);
  // here every id is given, so a user interface can select all of them.
  report["unconverged_faces"] = to_int_array(result.unconverged_faces);
  report["flipped_face_ids"] = to_int_array(result.flipped_faces);
  report["relabelled_faces"] = to_int_array(result.relabelled_faces);
  out["report"] = report;
  return out;
}

py::array_t<int> nearest_labels_py(const DoubleArray& vertices, const IntArray& face_indices,
                                   const IntArray& face_sizes) {
  const PolygonMesh mesh = to_mesh(vertices, face_indices, face_sizes);
  check_input(mesh);
  const std::vector<int> labels = nearest_labels(mesh);
  return to_int_array(labels);
}

py::dict figures_py(const DoubleArray& input, const DoubleArray& output, const IntArray& face_indices,
                    const IntArray& face_sizes, const IntArray& labels) {
  const PolygonMesh given = to_mesh(input, face_indices, face_sizes);
  const Vertices given_out = to_vertices(output, "output_vertices");
  if (given_out.rows() != given.vertices.rows())
    throw py::value_error("output_vertices has " + std::to_string(given_out.rows()) + " rows but input_vertices has " +
                          std::to_string(given.vertices.rows()));
  for (Eigen::Index v = 0; v < given_out.rows(); ++v)
    if (!given_out.row(v).allFinite())
      throw py::value_error("output_vertices[" + std::to_string(v) +
                            "] is not finite: a NaN or infinite "
                            "position has no figures");
  std::vector<int> face_labels = to_labels(labels);
  check_input(given, &face_labels);
  // Both through the input's unit box (unit_box.h): the figures are ratios, which
  // one similarity keeps, and raw squared lengths overflow above about 1e77.
  const UnitBoxMesh unit(given);
  const PolygonMesh& mesh = unit.mesh();
  const Vertices out = unit.box().to_unit(given_out);
  const std::vector<int> nearest = nearest_labels(mesh);
  for (size_t f = 0; f < face_labels.size(); ++f)
    if (face_labels[f] == kUnlabelled) face_labels[f] = nearest[f];
  const Triangulation triangulation = triangulate(mesh.vertices, mesh.faces);
  std::vector<int> triangle_labels(triangulation.face_of_triangle.size());
  for (size_t t = 0; t < triangle_labels.size(); ++t)
    triangle_labels[t] = face_labels[triangulation.face_of_triangle[t]];
  return figures_dict(QualityMeasure(mesh.vertices, triangulation.triangles, triangle_labels).measure(out));
}

py::dict refine_py(const DoubleArray& vertices, const IntArray& face_indices, const IntArray& face_sizes,
                   const std::optional<IntArray>& labels, int levels, const std::string& scheme) {
  const PolygonMesh mesh = to_mesh(vertices, face_indices, face_sizes);
  const std::vector<int> face_labels = labels ? to_labels(*labels) : std::vector<int>{};
  const RefineScheme parsed = parse_refine_scheme(scheme);
  Refined refined;
  {
    py::gil_scoped_release release;
    refined = refine(mesh, face_labels, levels, parsed);
  }
  std::vector<int> sizes(refined.mesh.faces.count());
  for (int f = 0; f < refined.mesh.faces.count(); ++f) sizes[f] = refined.mesh.faces.size(f);
  py::dict out;
  out["vertices"] = to_numpy(refined.mesh.vertices);
  out["face_indices"] = to_int_array(refined.mesh.faces.indices);
  out["face_sizes"] = to_int_array(sizes);
  out["labels"] = labels ? py::object(to_int_array(refined.labels)) : py::object(py::none());
  out["parent_face"] = to_int_array(refined.parent_face);
  return out;
}

py::tuple read_mesh_py(const std::string& path) {
  PolygonMesh mesh;
  {
    py::gil_scoped_release release;
    mesh = read_mesh(path);
  }
  std::vector<int> sizes(mesh.faces.count());
  for (int f = 0; f < mesh.faces.count(); ++f) sizes[f] = mesh.faces.size(f);
  return py::make_tuple(to_numpy(mesh.vertices), to_int_array(mesh.faces.indices), to_int_array(sizes));
}

// Labels (docs/design.md section 3): the automatic labeller, the validator and the orientation
// check; dicts through the same JSON writer as `polycube validate --json`.
py::array_t<int> auto_labels_py(const DoubleArray& vertices, const IntArray& face_indices, const IntArray& face_sizes,
                                double detail, std::optional<double> compactness, bool repair, bool straighten) {
  const PolygonMesh mesh = to_mesh(vertices, face_indices, face_sizes);
  AutoLabelOptions options = AutoLabelOptions::with_detail(detail);
  if (compactness) options.compactness = *compactness;
  options.repair = repair;
  if (!straighten) options.straighten_iterations = 0;
  std::vector<int> labels;
  {
    py::gil_scoped_release release;
    labels = auto_labels(mesh, options);
  }
  return to_int_array(labels);
}

py::dict validate_labels_py(const DoubleArray& vertices, const IntArray& face_indices, const IntArray& face_sizes,
                            const IntArray& labels) {
  const PolygonMesh mesh = to_mesh(vertices, face_indices, face_sizes);
  const std::vector<int> face_labels = to_labels(labels);
  LabelValidation validation;
  {
    py::gil_scoped_release release;
    validation = validate_labels(mesh, face_labels);
  }
  Json json = Json::object();
  add_validation(json, validation);
  return json_loads(json);
}

py::dict orientation_py(const DoubleArray& vertices, const IntArray& face_indices, const IntArray& face_sizes,
                        const std::optional<IntArray>& labels) {
  const PolygonMesh mesh = to_mesh(vertices, face_indices, face_sizes);
  std::vector<int> face_labels;
  if (labels) face_labels = to_labels(*labels);
  const Orientation o = orientation(mesh, labels ? &face_labels : nullptr);
  Json json = Json::object();
  add_orientation(json, o, labels.has_value());
  return json_loads(json);
}

py::array_t<int> flip_labels_py(const IntArray& labels) { return to_int_array(flip_labels(to_labels(labels))); }

py::array_t<int> read_labels_py(const std::string& path, int face_count) {
  return to_int_array(read_labels(path, face_count));
}

// Uses of the polycube: its UV map and its quad remesh.
Vertices polycube_positions(const DoubleArray& polycube, const PolygonMesh& mesh) {
  Vertices positions = to_vertices(polycube, "polycube");
  if (positions.rows() != mesh.vertices.rows())
    throw py::value_error("polycube has " + std::to_string(positions.rows()) + " rows but vertices has " +
                          std::to_string(mesh.vertices.rows()));
  return positions;
}

py::dict polycube_uv_py(const DoubleArray& vertices, const IntArray& face_indices, const IntArray& face_sizes,
                        const DoubleArray& polycube, const std::optional<IntArray>& labels, bool pack, double padding,
                        bool relax, double merge) {
  const PolygonMesh mesh = to_mesh(vertices, face_indices, face_sizes);
  const Vertices positions = polycube_positions(polycube, mesh);
  const std::vector<int> face_labels = labels ? to_ints(*labels, "labels") : std::vector<int>{};
  PolycubeUvOptions options;
  options.pack = pack;
  options.padding = padding;
  options.relax = relax || merge >= 0.0;
  options.merge_slack = merge;
  PolycubeUv uv;
  {
    py::gil_scoped_release release;
    uv = polycube_uv(mesh, positions, face_labels, options);
  }
  py::array_t<double> uvs({static_cast<py::ssize_t>(uv.uvs.rows()), py::ssize_t{2}});
  if (uv.uvs.size() > 0) std::memcpy(uvs.mutable_data(), uv.uvs.data(), sizeof(double) * uv.uvs.size());
  py::dict out;
  out["uvs"] = uvs;
  out["island_of_face"] = to_int_array(uv.island_of_face);
  out["label_of_face"] = to_int_array(uv.label_of_face);
  out["islands"] = uv.islands;
  return out;
}

py::dict uv_figures_py(const DoubleArray& vertices, const IntArray& face_indices, const IntArray& face_sizes,
                       const DoubleArray& uvs) {
  const PolygonMesh mesh = to_mesh(vertices, face_indices, face_sizes);
  check_input(mesh);
  if (uvs.ndim() != 2 || uvs.shape(1) != 2) throw py::value_error("uvs must be a (corners, 2) array");
  CornerUvs corner_uvs(uvs.shape(0), 2);
  if (uvs.size() > 0) std::memcpy(corner_uvs.data(), uvs.data(), sizeof(double) * uvs.size());
  const UvFigures f = uv_figures(mesh, corner_uvs);
  py::dict out;
  out["angle_distortion"] = f.angle_distortion;
  out["area_distortion"] = f.area_distortion;
  out["collapsed_area"] = f.collapsed_area;
  out["flipped"] = f.flipped;
  out["islands"] = f.islands;
  out["seam_length"] = f.seam_length;
  return out;
}

py::dict quad_remesh_py(const DoubleArray& vertices, const IntArray& face_indices, const IntArray& face_sizes,
                        const DoubleArray& polycube, const std::optional<IntArray>& labels, double edge_length,
                        int relax_iterations) {
  const PolygonMesh mesh = to_mesh(vertices, face_indices, face_sizes);
  const Vertices positions = polycube_positions(polycube, mesh);
  const std::vector<int> face_labels = labels ? to_ints(*labels, "labels") : std::vector<int>{};
  QuadRemeshOptions options;
  options.edge_length = edge_length;
  options.relax_iterations = relax_iterations;
  QuadRemesh remesh;
  {
    py::gil_scoped_release release;
    remesh = quad_remesh(mesh, positions, face_labels, options);
  }
  py::dict out;
  out["vertices"] = to_numpy(remesh.mesh.vertices);
  out["face_indices"] = to_int_array(remesh.mesh.faces.indices);
  out["face_sizes"] = to_int_array(std::vector<int>(remesh.mesh.faces.count(), 4));
  out["source_face"] = to_int_array(remesh.source_face);
  out["label"] = to_int_array(remesh.label);
  py::array_t<int> corners({remesh.vertex_corners.rows(), Eigen::Index{3}});
  std::memcpy(corners.mutable_data(), remesh.vertex_corners.data(), sizeof(int) * remesh.vertex_corners.size());
  py::array_t<double> weights({remesh.vertex_weights.rows(), Eigen::Index{3}});
  std::memcpy(weights.mutable_data(), remesh.vertex_weights.data(), sizeof(double) * remesh.vertex_weights.size());
  out["vertex_corners"] = corners;
  out["vertex_weights"] = weights;
  out["irregular_vertices"] = remesh.irregular_vertices;
  out["open_edges"] = remesh.open_edges;
  out["boundary_loops"] = remesh.boundary_loops;
  out["straightened_loops"] = remesh.straightened_loops;
  out["grid_spacing"] = remesh.grid_spacing;
  return out;
}

}  // namespace

PYBIND11_MODULE(polycube_native, m) {
  m.doc() = "Polycube deformation (Zhao et al.): the native solver of the polycube Blender add-on.";
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
  m.attr("LABEL_NAMES") = py::make_tuple("+X", "-X", "+Y", "-Y", "+Z", "-Z");
  // What the solver offers, for user interfaces: variants (default first) and
  // the labeller's default compactness.
  py::list variants;
  for (Variant variant : kVariants) variants.append(variant_name(variant));
  m.attr("VARIANTS") = py::tuple(variants);
  m.attr("DEFAULT_VARIANT") = variant_name(DeformOptions{}.variant);
  m.attr("DEFAULT_COMPACTNESS") = AutoLabelOptions{}.compactness;
  m.attr("DEFAULT_DETAIL") = 0.5;
  m.attr("MAX_REFINE_LEVELS") = kMaxRefineLevels;
  m.attr("DEFAULT_COARSE_TRIANGLES") = DeformOptions{}.coarse_triangles;

  m.def("deform", &deform_py, py::arg("vertices"), py::arg("face_indices"), py::arg("face_sizes"), py::arg("labels"),
        py::kw_only(), py::arg("iterations") = 100, py::arg("tolerance") = 0.5,
        py::arg("variant") = variant_name(DeformOptions{}.variant),
        py::arg("relabel_collapsed") = DeformOptions{}.relabel_collapsed,
        py::arg("rerun_from_result") = DeformOptions{}.rerun_from_result,
        py::arg("last_resort") = DeformOptions{}.last_resort, py::arg("polish") = DeformOptions{}.polish,
        py::arg("coarse_triangles") = DeformOptions{}.coarse_triangles, py::arg("callback") = py::none(), py::arg("stop") = py::none(), R"(Deform a mesh towards its polycube.

vertices (n, 3) float; face_indices: all face corners, flat; face_sizes: corners per face;
labels: per face, 0..5 = +X, -X, +Y, -Y, +Z, -Z, -1 = nearest axis.
callback(iteration, positions, figures) is called after every iteration; returning False stops.
relabel_collapsed (robust): an exact result that collapsed faces is run once more with them
relabelled, and that run kept when less collapses (docs/design.md section 2.6, stage 8; the
callback sees its result once, as the last iteration). stop() is polled after every iteration,
of the first run and of those runs, which the callback does not see, and within the stages whose
steps take minutes on large meshes (the untangling's rounds and Newton iterations, the polish's
steps); returning True stops the run at the iteration it is in and keeps what it had (a further
run stopped is not kept).
rerun_from_result (robust, 100,000 triangles and more): those runs start from the result instead
of the input, its charts moved past the relabelled faces and untangled around them: several times
faster, about as much collapsed, edge and area errors up to a sixth higher (stage 8).
last_resort (robust): a run that does not become an exact polycube is run once more, silently,
its flattening accepted up to half the area collapsed (stage 9; the report's last_resort says
when that run was kept), then once more with faces of opposite labels that meet back to back
relabelled (relabelled_faces lists them); False returns the first run's best state.
polish (robust): an exact result's edge and area errors are lowered last, its charts kept flat and
nothing turned over or newly collapsed (docs/design.md section 2.6, "Polish"; the report's
polish_steps counts the steps kept, and the callback sees the result once more, as the last
iteration); False returns the result as the run left it.
coarse_triangles (robust): a mesh of at least four times this many triangles is decimated to about
this many, its charts kept, deformed there and carried back, the fine run only finishing it
(docs/design.md section 2.8; the report's coarse_triangles and coarse_iterations say so); 0 deforms
every mesh at its own resolution.
Returns {"positions", "labels", "report"}; the report's face lists (unconverged_faces,
flipped_face_ids, relabelled_faces) hold every id, as int32 arrays. Raises ValueError on bad input.)");
  m.def("nearest_labels", &nearest_labels_py, py::arg("vertices"), py::arg("face_indices"), py::arg("face_sizes"),
        "Label every face by the axis nearest its normal.");
  m.def("figures", &figures_py, py::arg("input_vertices"), py::arg("output_vertices"), py::arg("face_indices"),
        py::arg("face_sizes"), py::arg("labels"),
        "The quality figures of output against input (docs/design.md section 4).");
  m.def("refine", &refine_py, py::arg("vertices"), py::arg("face_indices"), py::arg("face_sizes"),
        py::arg("labels") = py::none(), py::kw_only(), py::arg("levels") = 1, py::arg("scheme") = "bilinear",
        R"(Subdivide uniformly with OpenSubdiv (scheme bilinear, loop or catmark; levels 1..8).

Returns {"vertices", "face_indices", "face_sizes", "labels" (None without input labels), "parent_face"};
every child face keeps its parent's label.)");
  m.def("read_mesh", &read_mesh_py, py::arg("path"),
        "Read an .off, .obj or .ply file: (vertices (n, 3), face_indices, face_sizes). Raises ValueError.");
  m.def("read_labels", &read_labels_py, py::arg("path"), py::arg("face_count"),
        "Read a labels file (one integer -1..5 per face, '#' comments), as `polycube deform --labels FILE`. "
        "Raises ValueError naming the file and line.");

  m.def("auto_labels", &auto_labels_py, py::arg("vertices"), py::arg("face_indices"), py::arg("face_sizes"),
        py::kw_only(), py::arg("detail") = 0.5, py::arg("compactness") = py::none(), py::arg("repair") = true,
        py::arg("straighten") = true,
        R"(Label every face automatically: (F,) int32, 0..5 = +X, -X, +Y, -Y, +Z, -Z.

Straightens the shape so its normals gather on the axes (unless straighten=False), then a graph
cut (alpha-expansion) of fidelity to the straightened normals plus compactness * chart boundary
length, local repair of what breaks the polycube conditions, and relabelling of faces flat charts
would squeeze. detail (0..1): 0 few large charts, 1 many small ones; compactness, when given,
overrides the one detail sets (larger: fewer, rounder charts). Deterministic. Raises ValueError
on bad input.)");
  m.def("validate_labels", &validate_labels_py, py::arg("vertices"), py::arg("face_indices"), py::arg("face_sizes"),
        py::arg("labels"),
        R"(Check labels against the polycube conditions and their realisability (docs/design.md
sections 3.2 and 3.5).

Returns {"valid", "realisable", "charts", "boundaries", "corners", "unlabelled_faces",
"violations"}; each violation is {"kind", "chart", "label", "label_name", "others", "vertex",
"faces"} with kind "too_few_neighbours", "opposite_neighbours", "corner_too_many_charts",
"reversed_chart" (these make labels invalid), "turning_point" or "squeezed_faces" (these make
flat charts collapse faces). -1 labels are judged by their nearest axis. Raises ValueError on
bad input.)");
  m.def("orientation", &orientation_py, py::arg("vertices"), py::arg("face_indices"), py::arg("face_sizes"),
        py::arg("labels") = py::none(),
        R"(Check the winding: {"orientable", "consistent", "inconsistent_edges", "components",
"closed_components", "inward_components", "inward"}, and with labels "area_against_labels"
(share of the area facing away from its label) and "labels_opposite" (most of it does: labels
made for the other winding; flip_labels fixes them).)");
  m.def("supernodal_available", &supernodal_available,
        R"(Whether CHOLMOD's plugin (polycube_cholmod.so beside this module) loads; it is loaded
the first time a mesh of 50,000 vertices or more is solved, or by this call. Without it large
meshes factorise with Eigen's simplicial LDLT (the report's "solver" says which).)");
  m.def("flip_labels", &flip_labels_py, py::arg("labels"),
        "Every label turned to its opposite axis (+X <-> -X, ...), -1 kept.");

  m.def("polycube_uv", &polycube_uv_py, py::arg("vertices"), py::arg("face_indices"), py::arg("face_sizes"),
        py::arg("polycube"), py::arg("labels") = py::none(), py::kw_only(), py::arg("pack") = true,
        py::arg("padding") = PolycubeUvOptions{}.padding, py::arg("relax") = false, py::arg("merge") = -1.0,
        R"(A UV map from the mesh's polycube: one island per chart, the polycube's positions in the chart's plane.

polycube: (n, 3) positions of the same vertices on the polycube (the last shape key of a run);
labels: the labels the solver ended with, or None to read them from the polycube's normals.
Returns {"uvs" (corners, 2) in face_indices order, "island_of_face", "label_of_face", "islands"}.
pack: islands packed without overlap into the unit square, one texel density.
relax: each island re-solved to keep the mesh's angles (least-squares conformal), same islands and seams.
merge: >= 0 (implies relax): neighbouring islands merged where their union unfolds as a disk with
angle and area distortion each rising by at most this much (0.01 is a good start).
Raises ValueError on a polycube that does not fit the mesh or is folded (flipped faces).)");
  m.def("uv_figures", &uv_figures_py, py::arg("vertices"), py::arg("face_indices"), py::arg("face_sizes"),
        py::arg("uvs"),
        R"(How good a UV map (uvs: (corners, 2)) is: {"angle_distortion", "area_distortion" (area-weighted
means of each triangle's singular value ratio and of its area ratio max(r, 1/r); 1 is perfect),
"collapsed_area" (share of the area mapped to no UV area, left out of the means), "flipped",
"islands", "seam_length"}.)");
  m.def("quad_remesh", &quad_remesh_py, py::arg("vertices"), py::arg("face_indices"), py::arg("face_sizes"),
        py::arg("polycube"), py::arg("labels") = py::none(), py::kw_only(), py::arg("edge_length"),
        py::arg("relax_iterations") = QuadRemeshOptions{}.relax_iterations,
        R"(An all-quad mesh of the input from its exact polycube, quads of about edge_length (input units),
their vertices evened out on the input by relax_iterations sweeps (0: the grid as carried back).

Returns {"vertices", "face_indices", "face_sizes" (all 4), "source_face" (input face under each
quad), "label", "vertex_corners" and "vertex_weights" (each vertex as weights of three input face
corners, indices into face_indices: carries per-corner data such as UVs), "irregular_vertices",
"open_edges", "boundary_loops", "straightened_loops" (open boundary loops laid along grid lines),
"grid_spacing"}. Raises ValueError with one
sentence: not an exact polycube, a folded one, an edge length larger than the model, ...)");
}
