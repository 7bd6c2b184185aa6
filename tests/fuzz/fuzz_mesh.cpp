#include "fuzz_mesh.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "deform/deform.h"
#include "io/labels_io.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "labels/orientation.h"
#include "labels/validate_labels.h"

namespace polycube {
namespace {

const char* const kNames[] = {"fuzz.off", "fuzz.obj", "fuzz.ply"};

// Small meshes keep a run in milliseconds, so the fuzzer tries many inputs.
constexpr int kMaxFaces = 400;

[[noreturn]] void bug(const char* what) {
  std::fprintf(stderr, "fuzz_mesh: %s\n", what);
  std::abort();
}

}  // namespace

std::string fuzz_input(const std::string& name, const std::string& file_bytes) {
  const std::string ext = std::filesystem::path(name).extension().string();
  const char format = ext == ".off" ? 0 : ext == ".obj" ? 1 : 2;
  return std::string(1, format) + file_bytes;
}

int fuzz_mesh(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string name = kNames[data[0] % 3];
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  // The same bytes as a labels file, for the count the header byte gives.
  try {
    const std::vector<int> labels = parse_labels("fuzz.labels", bytes, data[0]);
    for (int label : labels)
      if (label < -1 || label > 5) bug("a label outside -1..5 was read");
  } catch (const Error&) {
  }
  PolygonMesh mesh;
  try {
    mesh = parse_mesh(name, bytes);
  } catch (const Error&) {
    return 0;
  }
  if (mesh.faces.count() > kMaxFaces) return 0;

  // What the reader accepted, the writer writes and the reader reads back unchanged.
  try {
    const PolygonMesh again = parse_mesh(name, mesh_file_bytes(name, mesh.vertices, mesh.faces));
    if (again.vertices != mesh.vertices || again.faces.indices != mesh.faces.indices ||
        again.faces.offsets != mesh.faces.offsets)
      bug("a written mesh reads back different");
  } catch (const Error&) {
  }

  // Labels from the input's own bytes: every value -1..5, unlabelled faces included.
  std::vector<int> labels(mesh.faces.count());
  for (size_t f = 0; f < labels.size(); ++f) labels[f] = data[(f * 7 + 1) % size] % 7 - 1;
  try {
    validate_labels(mesh, labels);
  } catch (const Error&) {
  }
  try {
    orientation(mesh, &labels);
  } catch (const Error&) {
  }
  DeformOptions options;
  options.iterations = 3;
  options.variant = kVariants[(data[0] / 3) % 3];
  try {
    const DeformResult result = deform(mesh, labels, options);
    if (result.positions.rows() != mesh.vertices.rows() || !result.positions.allFinite())
      bug("deform returned positions of the wrong size or non-finite ones");
  } catch (const Error&) {
  }
  return 0;
}

}  // namespace polycube
