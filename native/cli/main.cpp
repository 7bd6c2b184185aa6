// The `polycube` command-line program: the native core without Blender, for
// batch work, benchmarks and users outside Blender.
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>

#include "cli/commands.h"
#include "core/mesh.h"

namespace {

void print_usage(std::FILE* out) {
  std::fprintf(out, "usage: %s\nRun `polycube COMMAND --help` for one command.\n", polycube::kDeformUsage);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    print_usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  const bool help = args.size() == 1 && (args[0] == "--help" || args[0] == "-h");
  try {
    if (command == "deform") {
      if (help) return std::printf("usage: %s", polycube::kDeformUsage), 0;
      return polycube::deform_command(args);
    }
    std::fprintf(stderr, "polycube: unknown command '%s' (commands: deform)\n", command.c_str());
    return 2;
  } catch (const polycube::Error& e) {
    std::fprintf(stderr, "polycube %s: error: %s\n", command.c_str(), e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "polycube %s: error: out of memory\n", command.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "polycube %s: internal error: %s\n", command.c_str(), e.what());
    return 3;
  }
}
