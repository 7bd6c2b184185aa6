// The fuzz target: one input through the mesh and label readers, the validator, the
// orientation check and a short deformation, as a user's file would go.
// Shared by the libFuzzer program (`make fuzz`, main.cpp beside) and the
// regression test that replays the seeds and every input that once crashed
// (tests/native/test_fuzz_regressions.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace polycube {

// data[0] % 3 picks the format (0: OFF, 1: OBJ, 2: PLY), the rest is the
// file; it is also read as a labels file for data[0] faces. Bad input must end in polycube::Error; anything else (a crash, a
// sanitizer report, another exception, a write/read round trip that changes
// the mesh) is a bug and aborts.
int fuzz_mesh(const uint8_t* data, size_t size);

// A mesh file as a fuzz input: its format byte (by the extension of name) and its bytes.
std::string fuzz_input(const std::string& name, const std::string& file_bytes);

}  // namespace polycube
