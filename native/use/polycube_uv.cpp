#include "use/polycube_uv.h"

#include <deque>

#include "labels/charts.h"
#include "mesh/mesh_adjacency.h"
#include "use/merge_islands.h"
#include "use/pack_islands.h"
#include "use/polycube_surface.h"
#include "use/relax_islands.h"

namespace polycube {

PolycubeUv polycube_uv(const PolygonMesh& input, const Vertices& polycube, const std::vector<int>& labels,
                       const PolycubeUvOptions& options) {
  const PolycubeSurface surface = polycube_surface(input, polycube, labels);
  const int face_count = input.faces.count();
  const MeshAdjacency adjacency = mesh_adjacency(input.faces, static_cast<int>(input.vertices.rows()));
  const Charts chart = charts(adjacency, surface.face_label);

  // Islands: the charts that carry area, in chart order.
  std::vector<int> island_of_chart(chart.count(), -1);
  PolycubeUv out;
  for (int f = 0; f < face_count; ++f)
    if (surface.face_carries_area[f] && island_of_chart[chart.of_face[f]] < 0)
      island_of_chart[chart.of_face[f]] = out.islands++;
  out.island_of_face.assign(face_count, -1);
  out.label_of_face.assign(face_count, 0);
  std::deque<int> queue;
  for (int f = 0; f < face_count; ++f) {
    out.island_of_face[f] = island_of_chart[chart.of_face[f]];
    out.label_of_face[f] = surface.face_label[f];
    if (out.island_of_face[f] >= 0) queue.push_back(f);
  }
  // Faces of charts without area join a neighbouring island (and its plane), breadth first.
  const std::vector<std::vector<int>> neighbours = face_neighbours(adjacency, face_count);
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop_front();
    for (int g : neighbours[f])
      if (out.island_of_face[g] < 0) {
        out.island_of_face[g] = out.island_of_face[f];
        out.label_of_face[g] = out.label_of_face[f];
        queue.push_back(g);
      }
  }
  // A component with no area at all: one island of its own, a point.
  for (int f = 0; f < face_count; ++f)
    if (out.island_of_face[f] < 0) {
      out.island_of_face[f] = out.islands++;
      queue.push_back(f);
      while (!queue.empty()) {
        const int g = queue.front();
        queue.pop_front();
        for (int h : neighbours[g])
          if (out.island_of_face[h] < 0) {
            out.island_of_face[h] = out.island_of_face[f];
            queue.push_back(h);
          }
      }
    }

  // Projection on the plane of the face's label: (u, v) along the two other
  // axes in the order that keeps the winding (e_b x e_c = e_a for +a, swapped for -a).
  out.uvs.resize(static_cast<Eigen::Index>(input.faces.indices.size()), 2);
  for (int f = 0; f < face_count; ++f) {
    const int label = out.label_of_face[f], a = label / 2;
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const int u = label % 2 == 0 ? b : c, v = label % 2 == 0 ? c : b;
    for (int k = input.faces.offsets[f]; k < input.faces.offsets[f + 1]; ++k) {
      const int vertex = input.faces.indices[k];
      out.uvs.row(k) << polycube(vertex, u), polycube(vertex, v);
    }
  }
  if (options.relax) relax_islands(input, out.island_of_face, out.islands, out.uvs, surface.area_scale);
  if (options.relax && options.merge_slack >= 0.0)
    merge_islands(input, out.island_of_face, out.islands, out.uvs, surface.area_scale, options.merge_slack);
  if (options.pack) {
    std::vector<int> island_of_corner(input.faces.indices.size());
    for (int f = 0; f < face_count; ++f)
      for (int k = input.faces.offsets[f]; k < input.faces.offsets[f + 1]; ++k) island_of_corner[k] = out.island_of_face[f];
    pack_islands(out.uvs, island_of_corner, out.islands, options.padding);
  }
  return out;
}

}  // namespace polycube
