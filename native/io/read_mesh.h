// Reads a polygon mesh from an .off, .obj or .ply file (chosen by extension,
// any case), so the command-line program and the tests can load the same
// models the add-on gets from Blender.
//
// Readers are strict: a file that does not say exactly what its header or
// syntax promises is rejected with one sentence naming the path (and, for
// text, the line) rather than half-loaded, because a silently wrong mesh
// turns into a baffling solver failure much later.
#pragma once

#include <string>

#include "mesh/mesh.h"

namespace polycube {

// Throws Error on a missing or unreadable file, an unknown extension,
// malformed or truncated contents, non-finite coordinates, faces with fewer
// than 3 vertices or indices out of range. Faces keep file order; vertex
// indices are 0-based.
PolygonMesh read_mesh(const std::string& path);

// The same parsers over bytes in memory (the fuzz target, tests/fuzz): name
// picks the format by its extension and names the data in messages.
PolygonMesh parse_mesh(const std::string& name, const std::string& data);

// The whole file as bytes. Throws Error naming the path when it cannot be
// read. Shared with read_labels so both report missing files the same way.
std::string read_file(const std::string& path);

// Throws Error when path holds a NUL character: the system would see only
// the part before it, and a message would print only that part. Shared with
// the writers (output_files.h).
void check_path(const std::string& path);

}  // namespace polycube
