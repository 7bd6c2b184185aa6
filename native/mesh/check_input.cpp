#include "mesh/check_input.h"

#include <cmath>
#include <string>

namespace polycube {

void check_input(const PolygonMesh& mesh, const std::vector<int>* labels) {
  const PolygonFaces& faces = mesh.faces;
  const long vertex_count = static_cast<long>(mesh.vertices.rows());
  if (vertex_count == 0) throw Error("the mesh is empty: it has no vertices");
  if (faces.offsets.empty() || faces.offsets.front() != 0 ||
      faces.offsets.back() != static_cast<long>(faces.indices.size()))
    throw Error("face offsets do not match the face index array");
  if (faces.count() == 0) throw Error("the mesh has no faces, so there is nothing to deform");
  for (long v = 0; v < vertex_count; ++v)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(mesh.vertices(v, k)))
        throw Error("vertex " + std::to_string(v) + " has a non-finite coordinate (NaN or Inf)");
  for (int f = 0; f < faces.count(); ++f) {
    if (faces.size(f) < 3)
      throw Error("face " + std::to_string(f) + " has " + std::to_string(faces.size(f)) +
                  " corners; every face needs at least 3");
    for (int k = faces.offsets[f]; k < faces.offsets[f + 1]; ++k)
      if (faces.indices[k] < 0 || faces.indices[k] >= vertex_count)
        throw Error("face " + std::to_string(f) + " uses vertex index " + std::to_string(faces.indices[k]) +
                    ", but the mesh has only " + std::to_string(vertex_count) + " vertices");
  }
  if (labels == nullptr) return;
  if (static_cast<long>(labels->size()) != faces.count())
    throw Error("there are " + std::to_string(labels->size()) + " labels for " + std::to_string(faces.count()) +
                " faces; give one label per face");
  for (size_t f = 0; f < labels->size(); ++f)
    if ((*labels)[f] < -1 || (*labels)[f] > 5)
      throw Error("face " + std::to_string(f) + " has label " + std::to_string((*labels)[f]) +
                  ", outside -1..5 (0..5 = +X, -X, +Y, -Y, +Z, -Z; -1 = unlabelled)");
}

}  // namespace polycube
