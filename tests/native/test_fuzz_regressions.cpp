// Replays the fuzz target (tests/fuzz/fuzz_mesh.h) on its seeds and on every
// input that once made it fail (tests/fuzz/regressions/, raw fuzz inputs), in
// the ordinary build, so a fixed bug stays fixed without `make fuzz`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "fuzz_mesh.h"

namespace {

std::string bytes_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void replay(const std::string& input) {
  polycube::fuzz_mesh(reinterpret_cast<const uint8_t*>(input.data()), input.size());
}

TEST(FuzzRegressions, SeedsInEveryFormat) {
  int seeds = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(POLYCUBE_FUZZ_DATA) + "/seeds")) {
    const std::string input = polycube::fuzz_input(entry.path().filename(), bytes_of(entry.path()));
    SCOPED_TRACE(entry.path().string());
    for (char format = 0; format < 9; ++format) {  // every format byte: each parser and variant sees each seed
      std::string variant = input;
      variant[0] = format;
      replay(variant);
    }
    ++seeds;
  }
  EXPECT_GE(seeds, 7);
}

TEST(FuzzRegressions, InputsThatOnceFailed) {
  for (const auto& entry : std::filesystem::directory_iterator(std::string(POLYCUBE_FUZZ_DATA) + "/regressions")) {
    if (entry.path().filename() == "README") continue;
    SCOPED_TRACE(entry.path().string());
    replay(bytes_of(entry.path()));
  }
}

}  // namespace
