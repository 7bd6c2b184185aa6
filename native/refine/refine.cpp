#include "refine/refine.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <numeric>

#include "mesh/check_input.h"

namespace polycube {
namespace {

using namespace OpenSubdiv;

// OpenSubdiv reports topology problems through a global callback that prints;
// collect the first message so it can go into the Error instead.
std::mutex osd_mutex;
std::string osd_message;
void keep_osd_message(Far::ErrorType, const char* message) {
  if (osd_message.empty()) osd_message = message;
}

struct Point {
  double p[3];
  void Clear() { p[0] = p[1] = p[2] = 0.0; }
  void AddWithWeight(const Point& source, double weight) {
    for (int k = 0; k < 3; ++k) p[k] += weight * source.p[k];
  }
};

// OpenSubdiv keeps every level's topology: about 1 GiB per 5 million faces.
constexpr long kMaxFaces = 20'000'000;

}  // namespace

RefineScheme parse_refine_scheme(const std::string& name) {
  if (name == "bilinear") return RefineScheme::kBilinear;
  if (name == "loop") return RefineScheme::kLoop;
  if (name == "catmark") return RefineScheme::kCatmark;
  throw Error("unknown subdivision scheme '" + name + "': use bilinear, loop or catmark");
}

Refined refine(const PolygonMesh& mesh, const std::vector<int>& labels, int levels, RefineScheme scheme) {
  check_input(mesh, labels.empty() ? nullptr : &labels);
  if (levels < 1 || levels > kMaxRefineLevels)
    throw Error("refinement levels must be 1.." + std::to_string(kMaxRefineLevels) + ", got " +
                std::to_string(levels));
  const int face_count = mesh.faces.count();
  std::vector<int> sizes(face_count);
  for (int f = 0; f < face_count; ++f) sizes[f] = mesh.faces.size(f);
  const bool all_triangles = std::all_of(sizes.begin(), sizes.end(), [](int s) { return s == 3; });
  if (scheme == RefineScheme::kLoop && !all_triangles)
    throw Error("Loop subdivision needs a triangle mesh; use catmark or bilinear for polygons");
  if (face_count * std::pow(4.0, levels) > kMaxFaces)
    throw Error(std::to_string(levels) + " levels would make over " + std::to_string(kMaxFaces) +
                " faces; use fewer levels");

  // Linear interpolation on the triangle split (Loop topology) keeps all-triangle
  // meshes triangles, 1 -> 4; the bilinear scheme would split them into quads.
  Sdc::SchemeType type = Sdc::SCHEME_BILINEAR;
  if (scheme == RefineScheme::kLoop || (scheme == RefineScheme::kBilinear && all_triangles)) type = Sdc::SCHEME_LOOP;
  if (scheme == RefineScheme::kCatmark) type = Sdc::SCHEME_CATMARK;
  Sdc::Options options;
  options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);

  Far::TopologyDescriptor descriptor;
  descriptor.numVertices = static_cast<int>(mesh.vertices.rows());
  descriptor.numFaces = face_count;
  descriptor.numVertsPerFace = sizes.data();
  descriptor.vertIndicesPerFace = mesh.faces.indices.data();

  std::unique_ptr<Far::TopologyRefiner> refiner;
  {
    std::lock_guard<std::mutex> lock(osd_mutex);
    osd_message.clear();
    Far::SetErrorCallback(keep_osd_message);
    refiner.reset(Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(
        descriptor, Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options(type, options)));
    Far::SetErrorCallback(nullptr);
    if (!refiner) throw Error("OpenSubdiv cannot refine this mesh: " + (osd_message.empty() ? "bad topology" : osd_message));
  }
  Far::TopologyRefiner::UniformOptions uniform(levels);
  uniform.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uniform);

  // Each level's positions, labels and parents from the previous level's.
  std::vector<Point> points(mesh.vertices.rows());
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
    for (int k = 0; k < 3; ++k) points[v].p[k] = mesh.vertices(v, k);
  std::vector<int> face_labels = labels, parents(face_count);
  std::iota(parents.begin(), parents.end(), 0);
  Far::PrimvarRefinerReal<double> primvar(*refiner);
  for (int level = 1; level <= levels; ++level) {
    const Far::TopologyLevel& child = refiner->GetLevel(level);
    std::vector<Point> next(child.GetNumVertices());
    if (scheme == RefineScheme::kBilinear) primvar.InterpolateVarying(level, points, next);
    else primvar.Interpolate(level, points, next);
    points.swap(next);
    std::vector<int> next_parents(child.GetNumFaces());
    primvar.InterpolateFaceUniform(level, parents, next_parents);
    parents.swap(next_parents);
  }
  const Far::TopologyLevel& last = refiner->GetLevel(levels);
  Refined result;
  result.mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t v = 0; v < points.size(); ++v)
    for (int k = 0; k < 3; ++k) result.mesh.vertices(static_cast<Eigen::Index>(v), k) = points[v].p[k];
  result.mesh.faces.indices.reserve(static_cast<size_t>(last.GetNumFaceVertices()));
  result.mesh.faces.offsets.reserve(static_cast<size_t>(last.GetNumFaces()) + 1);
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const Far::ConstIndexArray corners = last.GetFaceVertices(f);
    result.mesh.faces.indices.insert(result.mesh.faces.indices.end(), corners.begin(), corners.end());
    result.mesh.faces.offsets.push_back(static_cast<int>(result.mesh.faces.indices.size()));
  }
  if (!face_labels.empty()) {
    result.labels.resize(parents.size());
    for (size_t f = 0; f < parents.size(); ++f) result.labels[f] = face_labels[parents[f]];
  }
  result.parent_face = std::move(parents);
  return result;
}

}  // namespace polycube
