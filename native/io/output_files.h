// The files one command writes, all of them or none: each is written in full
// to a temporary file beside its target (same directory, so the rename is
// atomic), and only when every one is written, and whatever else the command
// must do has succeeded, are they renamed into place. A failure anywhere
// (a missing directory, a full disk, a later error) leaves no file new or
// half-written, and an existing file at a target keeps its old contents.
//
//   OutputFiles outputs;
//   outputs.stage("fandisk.obj", mesh_bytes);    // throws Error naming the path
//   outputs.stage("fandisk.json", report);
//   print_summary();                             // may still fail: nothing is in place yet
//   outputs.commit();
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace polycube {

class ByteSink;
// Writes a file's bytes into a ByteSink.
using FileWriter = std::function<void(ByteSink&)>;

class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  // Removes every temporary file not yet committed.
  ~OutputFiles();

  // Writes bytes to a new temporary file in path's directory. Throws Error
  // with one sentence naming path (directory missing, path is a directory,
  // permission, disk full, NUL in the path); the temporaries staged so far
  // stay staged, and go when this object does.
  void stage(const std::string& path, std::string_view bytes);
  // The same, the bytes produced by write in chunks (byte_sink.h), so they
  // are never all in memory; write may throw Error too.
  void stage(const std::string& path, const FileWriter& write);

  // Renames every staged file onto its target, in staging order. If one
  // rename fails, removes the temporaries left and the targets this call
  // created (targets it replaced cannot be brought back), then throws Error.
  void commit();

 private:
  struct Staged {
    std::string path, temporary;
    bool existed = false;
  };
  std::vector<Staged> staged_;
};

// One file, atomically: stage and commit.
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace polycube
