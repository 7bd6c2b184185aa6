// The `polycube` command-line program: the native core without Blender, for
// batch work, benchmarks and users outside Blender.
#include <malloc.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <new>

#include "cli/commands.h"
#include "cli/flush_stdout.h"
#include "mesh/mesh.h"

namespace {

struct Command {
  const char* name;
  const char* usage;
  int (*run)(const std::vector<std::string>&);
};

const Command kCommands[] = {
    {"deform", "deform IN [--labels nearest|auto|FILE] [--output OUT] [--report REPORT.json] ...\n"
               "      deforms the mesh into its polycube and prints the quality figures",
     polycube::deform_command},
    {"label", "label IN --output LABELS.txt [--detail D] [--plain] ...\n"
              "      labels every face automatically",
     polycube::label_command},
    {"validate", "validate IN --labels FILE|auto|nearest [--json] ...\n"
                 "      checks labels against the polycube conditions",
     polycube::validate_command},
    {"refine", "refine IN --levels K --output OUT [--scheme bilinear|loop|catmark] [--labels FILE]\n"
               "      subdivides with OpenSubdiv so a coarse mesh can bend into a polycube",
     polycube::refine_command},
    {"uv", "uv IN POLYCUBE --output OUT.obj [--relax] [--merge SLACK] ...\n"
           "      a UV map from the polycube, one island per chart",
     polycube::uv_command},
    {"remesh", "remesh IN POLYCUBE --edge-length H --output OUT\n"
               "      an all-quad mesh from the exact polycube",
     polycube::remesh_command},
};

void print_usage(std::FILE* out) {
  std::fprintf(out, "usage: polycube COMMAND ...\n");
  for (const Command& command : kCommands) std::fprintf(out, "  polycube %s\n", command.usage);
  std::fprintf(out, "Run `polycube COMMAND --help` for one command's options.\n");
}

// What a command printed must reach stdout, or the exit status says it did not.
int finish(const char* program, int status) {
  try {
    polycube::flush_stdout();
  } catch (const polycube::Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return 1;
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  // One malloc arena: the flat charts' factors are made on worker threads
  // (deform/chart_planes.h) and freed by the main thread, and with an arena
  // per thread the blocks they leave serve only their own thread (B0's peak
  // up to 25.5 MiB instead of 24.6). The threads allocate seldom and in
  // large blocks, so they do not queue on one arena.
  mallopt(M_ARENA_MAX, 1);
  // Freed memory kept for the next allocation rather than given back to the
  // system: at scale a process makes and frees several chart factors of
  // hundreds of MiB, and memory given back is handed out again as fresh
  // pages the kernel clears first (B0 refined 64 times: a tenth of the run's
  // CPU time; 16.4 -> 15.7 s, peak +2%). Large blocks come from the heap too
  // (mmap only when the heap cannot grow), or they would be given back
  // whenever freed.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    print_usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : finish("polycube", 0);
  }
  const std::string name = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  const Command* command = nullptr;
  for (const Command& c : kCommands)
    if (name == c.name) command = &c;
  if (!command) {
    std::fprintf(stderr, "polycube: unknown command '%s' (run `polycube --help`)\n", name.c_str());
    return 2;
  }
  try {
    const int status = command->run(args);
    polycube::flush_stdout();
    return status;
  } catch (const polycube::Error& e) {
    std::fprintf(stderr, "polycube %s: error: %s\n", name.c_str(), e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "polycube %s: error: out of memory\n", name.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "polycube %s: internal error: %s\n", name.c_str(), e.what());
    return 3;
  }
}
