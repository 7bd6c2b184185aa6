// Bytes on their way to a file, handed on in chunks: a mesh of a million faces
// is written without its whole text (tens of MiB) in memory at once, which
// keeps a command's peak memory near the mesh's own.
//
//   ByteSink sink([&](std::string_view chunk) { write(fd, chunk); });
//   sink += "v ";  sink.put(0.5);  sink += '\n';
//   sink.flush();                      // the rest
//
// Without a drain it keeps everything: take() returns it.
#pragma once

#include <charconv>
#include <functional>
#include <string>
#include <string_view>

namespace polycube {

class ByteSink {
 public:
  using Drain = std::function<void(std::string_view)>;
  static constexpr size_t kChunk = 1 << 16;

  explicit ByteSink(Drain drain = {}) : drain_(std::move(drain)) {
    if (drain_) buffer_.reserve(kChunk + 256);
  }

  ByteSink& operator+=(char c) {
    buffer_ += c;
    return spill();
  }
  ByteSink& operator+=(std::string_view bytes) {
    buffer_ += bytes;
    return spill();
  }
  // Shortest text that reads back to the same number (std::to_chars).
  template <class Number>
  ByteSink& put(Number x) {
    char text[32];
    buffer_.append(text, std::to_chars(text, text + sizeof text, x).ptr);
    return spill();
  }
  void reserve(size_t bytes) {
    if (!drain_) buffer_.reserve(bytes);
  }

  // Hands what is buffered to the drain.
  void flush() {
    if (drain_ && !buffer_.empty()) drain_(buffer_);
    if (drain_) buffer_.clear();
  }
  std::string take() { return std::move(buffer_); }

 private:
  ByteSink& spill() {
    if (drain_ && buffer_.size() >= kChunk) flush();
    return *this;
  }

  Drain drain_;
  std::string buffer_;
};

}  // namespace polycube
