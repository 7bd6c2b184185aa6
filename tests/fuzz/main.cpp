// libFuzzer's entry (clang -fsanitize=fuzzer, `make fuzz`).
#include "fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return polycube::fuzz_mesh(data, size); }
