#include "cli/flush_stdout.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "mesh/mesh.h"

namespace polycube {

void flush_stdout() {
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return;
  const int err = errno;
  throw Error(std::string("cannot write to standard output: ") +
              (err ? std::strerror(err) : "an earlier write failed"));
}

}  // namespace polycube
