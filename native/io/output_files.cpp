// Temporary names are opened with O_EXCL, so a file of the user's that
// happens to have the name is never overwritten, and with mode 0666 so the
// result gets the permissions the umask gives any new file.
#include "io/output_files.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "io/byte_sink.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"

namespace polycube {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error("cannot write " + path + ": " + what);
}

// Why a file cannot be created at path, in the user's terms.
[[noreturn]] void fail_to_create(const std::string& path, int err) {
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::exists(parent, ec)) fail(path, "directory " + parent.string() + " does not exist");
  if (!parent.empty() && !fs::is_directory(parent, ec)) fail(path, parent.string() + " is not a directory");
  fail(path, std::strerror(err));
}

bool write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes.remove_prefix(static_cast<size_t>(n));
  }
  return true;
}

std::atomic<unsigned> temporary_counter{0};

}  // namespace

OutputFiles::~OutputFiles() {
  for (const Staged& s : staged_) ::unlink(s.temporary.c_str());
}

void OutputFiles::stage(const std::string& path, std::string_view bytes) {
  stage(path, [bytes](ByteSink& out) { out += bytes; });
}

void OutputFiles::stage(const std::string& path, const FileWriter& write) {
  check_path(path);
  std::error_code ec;
  if (path.empty()) throw Error("cannot write a file with an empty name");
  if (fs::is_directory(path, ec)) fail(path, "it is a directory");
  const fs::path target(path);
  const std::string base = target.filename().string();
  if (base.empty() || base == "." || base == "..") fail(path, "it names a directory, not a file");
  int fd = -1;
  std::string temporary;
  for (int attempt = 0; fd < 0; ++attempt) {
    temporary = (target.parent_path() / ("." + base + "." + std::to_string(::getpid()) + "." +
                                         std::to_string(temporary_counter++) + ".tmp"))
                    .string();
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && (errno != EEXIST || attempt > 100)) fail_to_create(path, errno);
  }
  staged_.push_back({path, temporary, fs::exists(target, ec)});
  bool ok = true;
  int err = 0;
  try {
    ByteSink sink([&](std::string_view chunk) {
      if (ok && !write_all(fd, chunk)) {
        ok = false;
        err = errno;
      }
    });
    write(sink);
    sink.flush();
  } catch (...) {
    ::close(fd);
    throw;
  }
  // close reports what a network filesystem could not store.
  if (::close(fd) != 0 && ok) {
    ok = false;
    err = errno;
  }
  if (!ok) fail(path, std::strerror(err));
}

void OutputFiles::commit() {
  for (size_t k = 0; k < staged_.size(); ++k) {
    if (::rename(staged_[k].temporary.c_str(), staged_[k].path.c_str()) == 0) continue;
    const int err = errno;
    for (size_t j = 0; j < k; ++j)
      if (!staged_[j].existed) ::unlink(staged_[j].path.c_str());
    const std::string path = staged_[k].path;
    staged_.erase(staged_.begin(), staged_.begin() + static_cast<long>(k));  // the rest: removed by ~OutputFiles
    fail(path, std::strerror(err));
  }
  staged_.clear();
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
  OutputFiles outputs;
  outputs.stage(path, bytes);
  outputs.commit();
}

}  // namespace polycube
