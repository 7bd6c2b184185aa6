#include "cli/flush_stdout.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "mesh/mesh.h"

namespace polycube {

namespace {

[[noreturn]] void fail(int err) {
  throw Error(std::string("cannot write to standard output: ") + (err ? std::strerror(err) : "an earlier write failed"));
}

}  // namespace

void print_line(std::string_view text) {
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fputc('\n', stdout) == EOF)
    fail(errno);
}

void flush_stdout() {
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return;
  fail(errno);
}

}  // namespace polycube
