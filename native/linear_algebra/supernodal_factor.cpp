#include "linear_algebra/supernodal_factor.h"

#include <dlfcn.h>
#include <link.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <string>

namespace polycube {
namespace {

using NewFactor = SupernodalFactor* (*)();

// The file this code was linked into: the program (its path from
// /proc/self/exe) or the Python module.
std::string own_file() {
  struct Search {
    std::uintptr_t address;
    std::string file;
    bool found = false;
  } search{reinterpret_cast<std::uintptr_t>(&own_file), {}};
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* data) {
        auto& s = *static_cast<Search*>(data);
        for (int i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& segment = info->dlpi_phdr[i];
          const std::uintptr_t start = info->dlpi_addr + segment.p_vaddr;
          if (segment.p_type == PT_LOAD && s.address >= start && s.address < start + segment.p_memsz) {
            s.file = info->dlpi_name ? info->dlpi_name : "";
            s.found = true;
            return 1;
          }
        }
        return 0;
      },
      &search);
  if (search.found && search.file.empty()) {  // the main program
    char path[4096];
    const ssize_t length = readlink("/proc/self/exe", path, sizeof(path) - 1);
    if (length > 0) search.file.assign(path, static_cast<size_t>(length));
  }
  return search.file;
}

// OpenBLAS (Debian's is built with pthreads) runs its level-3 calls on one
// thread per core, and a thread waiting for the others spins on sched_yield.
// On two cores shared with other work, the other thread is often not
// running: armadillo refined 16 times spent a third of its time in the
// kernel's scheduler (docs/design.md section 2.6, "Cost"). One thread, unless
// the user asked for more (OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS,
// OMP_NUM_THREADS, which OpenBLAS reads itself). Looked up through the
// plugin's handle: its libraries are not in the process's namespace, and a
// BLAS other than OpenBLAS has no such function.
void single_threaded_blas(void* handle) {
  for (const char* variable : {"OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS"})
    if (std::getenv(variable)) return;
  using SetThreads = void (*)(int);
  if (auto set_threads = reinterpret_cast<SetThreads>(dlsym(handle, "openblas_set_num_threads"))) set_threads(1);
}

NewFactor load_plugin() {
  const std::string file = own_file();
  const size_t slash = file.rfind('/');
  if (slash == std::string::npos) return nullptr;
  const std::string plugin = file.substr(0, slash + 1) + "polycube_cholmod.so";
  // RTLD_LOCAL: CHOLMOD's and the BLAS's symbols stay out of the process's
  // global namespace (Blender has its own libraries).
  void* handle = dlopen(plugin.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) return nullptr;
  single_threaded_blas(handle);
  return reinterpret_cast<NewFactor>(dlsym(handle, "polycube_new_supernodal_factor"));
}

NewFactor plugin() {
  static std::once_flag once;
  static NewFactor new_factor = nullptr;
  std::call_once(once, [] { new_factor = load_plugin(); });
  return new_factor;
}

}  // namespace

std::unique_ptr<SupernodalFactor> make_supernodal_factor() {
  const NewFactor new_factor = plugin();
  return std::unique_ptr<SupernodalFactor>(new_factor ? new_factor() : nullptr);
}

bool supernodal_available() { return plugin() != nullptr; }

}  // namespace polycube
