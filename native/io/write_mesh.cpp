// Mesh writers. Each format goes through a ByteSink, in chunks, to a
// temporary file that OutputFiles renames into place only once complete: a
// failure midway (disk full) cannot leave a truncated mesh where a good one
// was. The mesh is checked first, so we never write a file read_mesh would
// reject.
#include "io/write_mesh.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include "io/byte_sink.h"
#include "io/output_files.h"

namespace polycube {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error("cannot write " + path + ": " + what);
}

void check_mesh(const std::string& path, const Vertices& v, const PolygonFaces& f) {
  if (f.offsets.empty() || f.offsets.front() != 0 ||
      f.offsets.back() != static_cast<long long>(f.indices.size()))
    fail(path, "the face offsets do not match the face indices");
  for (int i = 0; i < f.count(); ++i) {
    if (f.size(i) < 3)
      fail(path, "face " + std::to_string(i) + " has " + std::to_string(f.size(i)) +
                     " vertices, a face needs at least 3");
    for (int k = f.offsets[i]; k < f.offsets[i + 1]; ++k)
      if (f.indices[k] < 0 || f.indices[k] >= v.rows())
        fail(path, "face " + std::to_string(i) + " uses vertex " + std::to_string(f.indices[k]) +
                       ", but there are only " + std::to_string(v.rows()) + " vertices");
  }
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (!v.row(i).allFinite()) fail(path, "vertex " + std::to_string(i) + " has a non-finite coordinate");
}

// "x y z\n"
void put_vertex(ByteSink& out, const Vertices& v, Eigen::Index i) {
  out.put(v(i, 0)) += ' ';
  out.put(v(i, 1)) += ' ';
  out.put(v(i, 2)) += '\n';
}

// uvs: null, or one (u, v) per corner, written as `vt` lines and `f v/vt` corners.
void write_obj(ByteSink& out, const Vertices& v, const PolygonFaces& f, const CornerUvs* uvs = nullptr) {
  out.reserve(v.rows() * 64 + f.indices.size() * (uvs ? 60 : 9) + f.count() * 3);
  out += "# polycube: " + std::to_string(v.rows()) + " vertices, " + std::to_string(f.count()) + " faces\n";
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    out += "v ";
    put_vertex(out, v, i);
  }
  if (uvs)
    for (Eigen::Index c = 0; c < uvs->rows(); ++c) {
      out += "vt ";
      out.put((*uvs)(c, 0)) += ' ';
      out.put((*uvs)(c, 1)) += '\n';
    }
  for (int i = 0; i < f.count(); ++i) {
    out += 'f';
    for (int k = f.offsets[i]; k < f.offsets[i + 1]; ++k) {
      out += ' ';
      out.put(f.indices[k] + 1LL);  // OBJ counts from 1
      if (uvs) {
        out += '/';
        out.put(k + 1LL);
      }
    }
    out += '\n';
  }
}

void write_off(ByteSink& out, const Vertices& v, const PolygonFaces& f) {
  out.reserve(v.rows() * 64 + f.indices.size() * 9 + f.count() * 4);
  out += "OFF\n" + std::to_string(v.rows()) + " " + std::to_string(f.count()) + " 0\n";
  for (Eigen::Index i = 0; i < v.rows(); ++i) put_vertex(out, v, i);
  for (int i = 0; i < f.count(); ++i) {
    out.put(f.size(i));
    for (int k = f.offsets[i]; k < f.offsets[i + 1]; ++k) {
      out += ' ';
      out.put(f.indices[k]);
    }
    out += '\n';
  }
}

// Appends the little-endian bytes of x.
template <class T>
void put_le(ByteSink& out, T x) {
  char b[sizeof(T)];
  std::memcpy(b, &x, sizeof(T));
  const uint16_t one = 1;
  if (*reinterpret_cast<const unsigned char*>(&one) == 0) std::reverse(b, b + sizeof(T));
  out += std::string_view(b, sizeof(T));
}

void write_ply(ByteSink& out, const Vertices& v, const PolygonFaces& f) {
  // Faces with more than 255 corners need a wider length than the usual uchar.
  int largest = 0;
  for (int i = 0; i < f.count(); ++i) largest = std::max(largest, f.size(i));
  bool wide = largest > 255;
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment written by polycube\n"
      "element vertex " +
      std::to_string(v.rows()) +
      "\nproperty double x\nproperty double y\nproperty double z\n"
      "element face " +
      std::to_string(f.count()) +
      (wide ? "\nproperty list int int vertex_indices\n" : "\nproperty list uchar int vertex_indices\n") +
      "end_header\n";
  out.reserve(header.size() + v.rows() * 24 + f.indices.size() * 4 + f.count() * (wide ? 4 : 1));
  out += header;
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    for (int c = 0; c < 3; ++c) put_le(out, v(i, c));
  for (int i = 0; i < f.count(); ++i) {
    if (wide)
      put_le<int32_t>(out, f.size(i));
    else
      put_le<uint8_t>(out, static_cast<uint8_t>(f.size(i)));
    for (int k = f.offsets[i]; k < f.offsets[i + 1]; ++k) put_le<int32_t>(out, f.indices[k]);
  }
}

// The lower-case extension of a path write_mesh writes, else Error.
std::string mesh_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".obj" && ext != ".off" && ext != ".ply")
    fail(path, ext.empty() ? "no file extension, expected .obj, .off or .ply"
                           : "unknown mesh format '" + ext + "', expected .obj, .off or .ply");
  return ext;
}

}  // namespace

void check_mesh_path(const std::string& path) { mesh_extension(path); }

FileWriter mesh_file_writer(const std::string& path, const Vertices& v, const PolygonFaces& f) {
  const std::string ext = mesh_extension(path);
  check_mesh(path, v, f);
  if (ext == ".obj") return [&v, &f](ByteSink& out) { write_obj(out, v, f); };
  if (ext == ".off") return [&v, &f](ByteSink& out) { write_off(out, v, f); };
  return [&v, &f](ByteSink& out) { write_ply(out, v, f); };
}

std::string mesh_file_bytes(const std::string& path, const Vertices& v, const PolygonFaces& f) {
  ByteSink bytes;
  mesh_file_writer(path, v, f)(bytes);
  return bytes.take();
}

void write_mesh(const std::string& path, const Vertices& v, const PolygonFaces& f) {
  OutputFiles outputs;
  outputs.stage(path, mesh_file_writer(path, v, f));
  outputs.commit();
}

FileWriter obj_with_uvs_writer(const std::string& path, const Vertices& v, const PolygonFaces& f,
                               const CornerUvs& uvs) {
  check_mesh(path, v, f);
  if (uvs.rows() != static_cast<Eigen::Index>(f.indices.size()))
    fail(path, std::to_string(uvs.rows()) + " UVs for " + std::to_string(f.indices.size()) + " face corners");
  if (!uvs.allFinite()) fail(path, "a UV coordinate is not finite");
  return [&v, &f, &uvs](ByteSink& out) { write_obj(out, v, f, &uvs); };
}

void write_obj_with_uvs(const std::string& path, const Vertices& v, const PolygonFaces& f, const CornerUvs& uvs) {
  OutputFiles outputs;
  outputs.stage(path, obj_with_uvs_writer(path, v, f, uvs));
  outputs.commit();
}

}  // namespace polycube
