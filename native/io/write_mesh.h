// Writes a polygon mesh as .obj, .off or .ply (binary little-endian),
// chosen by extension (any case), so results can be opened in any viewer and
// read back bit-exactly by read_mesh.
#pragma once

#include <string>

#include "io/output_files.h"
#include "mesh/mesh.h"

namespace polycube {

// Coordinates are written with the shortest text that reads back to the
// same double (or as raw doubles in PLY), so a round trip is lossless.
// Throws Error with one sentence naming the path if the extension is
// unknown, the mesh is inconsistent (index out of range, face with fewer
// than 3 vertices, non-finite coordinate) or the file cannot be written.
// Atomic (output_files.h): an existing file at path is replaced only once
// the new one is complete, and a failure leaves nothing behind.
void write_mesh(const std::string& path, const Vertices& v, const PolygonFaces& f);

// An .obj with one `vt` per face corner (uvs: #corners by 2, faces.indices
// order) and `f v/vt` corners, so UV seams survive. Same checks as write_mesh.
void write_obj_with_uvs(const std::string& path, const Vertices& v, const PolygonFaces& f, const CornerUvs& uvs);
// Its writer, for OutputFiles::stage, as mesh_file_writer.
FileWriter obj_with_uvs_writer(const std::string& path, const Vertices& v, const PolygonFaces& f,
                               const CornerUvs& uvs);

// Throws write_mesh's Error when `path` names no format it writes (.obj,
// .off, .ply): the commands check their outputs before the work, which
// can take minutes, rather than after.
void check_mesh_path(const std::string& path);

// What write_mesh writes, for OutputFiles::stage when a command writes
// several files all or none: checks path and mesh now (the same errors, the
// write aside), writes when called, in chunks. v and f must outlive it.
FileWriter mesh_file_writer(const std::string& path, const Vertices& v, const PolygonFaces& f);

// The same bytes, whole, in memory.
std::string mesh_file_bytes(const std::string& path, const Vertices& v, const PolygonFaces& f);

}  // namespace polycube
