// The mesh types every part of the core shares.
//
// Row-major storage matches numpy's C order, so the Python module copies
// positions in and out with one memcpy.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

namespace polycube {

using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
// One (u, v) per face corner, in PolygonFaces::indices order (UVs part at seams).
using CornerUvs = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

// Polygon faces as Blender and OBJ keep them: face f uses
// indices[offsets[f] .. offsets[f+1]). offsets has one entry more than faces.
struct PolygonFaces {
  std::vector<int> indices;
  std::vector<int> offsets{0};

  int count() const { return static_cast<int>(offsets.size()) - 1; }
  int size(int f) const { return offsets[f + 1] - offsets[f]; }
  void add(std::initializer_list<int> face) {
    indices.insert(indices.end(), face.begin(), face.end());
    offsets.push_back(static_cast<int>(indices.size()));
  }
};

struct PolygonMesh {
  Vertices vertices;
  PolygonFaces faces;
};

// Every failure the caller should see as a message (bad input, a file that
// cannot be read, a solver that broke down). The Python module turns it into
// ValueError, the command-line program into one line on stderr.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace polycube
