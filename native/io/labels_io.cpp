// Label files: strict on values and count, because a label shifted by one
// face still "works" and silently yields the wrong polycube.
#include "io/labels_io.h"

#include <algorithm>
#include <charconv>
#include <string_view>

#include "mesh/mesh.h"
#include "io/read_mesh.h"
#include "io/output_files.h"

namespace polycube {
namespace {

constexpr const char* kConvention = "0..5 = +X,-X,+Y,-Y,+Z,-Z, -1 = unlabelled";

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

}  // namespace

std::vector<int> read_labels(const std::string& path, int face_count) {
  if (face_count < 0) throw Error(path + ": cannot read labels for a negative face count");
  return parse_labels(path, read_file(path), face_count);
}

std::vector<int> parse_labels(const std::string& path, const std::string& data, int face_count) {
  if (face_count < 0) throw Error(path + ": cannot read labels for a negative face count");
  std::vector<int> labels;
  labels.reserve(std::min<size_t>(face_count, data.size() / 2 + 1));
  long line = 1;
  auto fail = [&](const std::string& what) {
    throw Error(path + " line " + std::to_string(line) + ": " + what);
  };
  const char* p = data.data();
  const char* end = p + data.size();
  if (data.compare(0, 3, "\xEF\xBB\xBF") == 0) p += 3;  // UTF-8 byte order mark
  while (p < end) {
    if (*p == '\n') ++line;
    if (is_space(*p)) {
      ++p;
    } else if (*p == '#') {
      while (p < end && *p != '\n') ++p;
    } else {
      const char* start = p;
      while (p < end && !is_space(*p) && *p != '#') ++p;
      std::string_view token(start, p - start);
      long long value = 0;
      const char* digits = token.size() > 1 && token[0] == '+' && token[1] != '-' ? start + 1 : start;
      auto r = std::from_chars(digits, p, value);
      if (r.ptr != p || r.ec != std::errc()) {
        std::string shown(token.substr(0, 40));
        for (char& c : shown)
          if (static_cast<unsigned char>(c) < 0x20) c = '?';  // keep binary junk off the terminal
        fail("expected an integer label, got '" + shown + "'");
      }
      if (value < -1 || value > 5)
        fail("label " + std::string(token) + " is outside -1..5 (" + kConvention + ")");
      labels.push_back(static_cast<int>(value));
    }
  }
  if (static_cast<long long>(labels.size()) != face_count)
    throw Error(path + " has " + std::to_string(labels.size()) + " labels but the mesh has " +
                std::to_string(face_count) + " faces");
  return labels;
}

std::string labels_file_text(const std::string& path, const std::vector<int>& labels, LabelsHeader header) {
  std::string out;
  if (header == LabelsHeader::kComment)
    out = std::string("# polycube face labels, one per face in face order: ") + kConvention + "\n";
  out.reserve(out.size() + labels.size() * 3);
  for (size_t f = 0; f < labels.size(); ++f) {
    if (labels[f] < -1 || labels[f] > 5)
      throw Error("cannot write " + path + ": face " + std::to_string(f) + " has label " +
                  std::to_string(labels[f]) + ", outside -1..5 (" + kConvention + ")");
    out += std::to_string(labels[f]);
    out += '\n';
  }
  return out;
}

void write_labels(const std::string& path, const std::vector<int>& labels, LabelsHeader header) {
  write_file_atomically(path, labels_file_text(path, labels, header));
}

}  // namespace polycube
