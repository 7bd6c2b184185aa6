// OFF, OBJ and PLY parsers over a file read whole into memory.
//
// One buffer and std::from_chars (no streams, no locale, no per-token
// allocation) keep million-face meshes to a fraction of a second, and
// walking the buffer ourselves makes line-numbered messages free.
// Counts from a header are checked against the bytes that follow before
// anything is allocated, so a corrupt count fails fast instead of asking
// for gigabytes.
#include "io/read_mesh.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

namespace polycube {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw Error(path + ": " + what); }

[[noreturn]] void fail_at(const std::string& path, long line, const std::string& what) {
  throw Error(path + " line " + std::to_string(line) + ": " + what);
}

// A token as shown in a message: quoted, and cut short so a binary blob
// mistaken for text cannot flood the terminal.
std::string quoted(std::string_view token) {
  std::string s(token.substr(0, 40));
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  return "'" + s + (token.size() > 40 ? "...'" : "'");
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Whitespace-separated tokens of one line.
class Tokens {
 public:
  explicit Tokens(std::string_view line) : rest_(line) {}

  bool next(std::string_view& token) {
    size_t i = 0;
    while (i < rest_.size() && is_space(rest_[i])) ++i;
    size_t j = i;
    while (j < rest_.size() && !is_space(rest_[j])) ++j;
    token = rest_.substr(i, j - i);
    rest_.remove_prefix(j);
    return !token.empty();
  }

  bool empty() const {
    std::string_view t;
    Tokens copy = *this;
    return !copy.next(t);
  }

 private:
  std::string_view rest_;
};

// The lines of a text buffer that hold something, numbered for messages.
class Lines {
 public:
  Lines(std::string_view text, bool strip_comments, long first_number = 1)
      : text_(text), number_(first_number - 1), comments_(strip_comments) {}

  // Skips blank lines and, if asked, '#' comments (also at the end of a line).
  bool next(std::string_view& line) {
    while (pos_ < text_.size()) {
      size_t end = text_.find('\n', pos_);
      if (end == std::string_view::npos) end = text_.size();
      std::string_view l = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++number_;
      if (comments_) l = l.substr(0, l.find('#'));
      for (char c : l)
        if (!is_space(c)) {
          line = l;
          return true;
        }
    }
    pos_ = text_.size();
    return false;
  }

  long number() const { return number_; }
  size_t remaining() const { return text_.size() - std::min(pos_, text_.size()); }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  long number_;
  bool comments_;
};

// from_chars rejects a leading '+', which strtod, and so other tools,
// accept.
const char* skip_plus(const char* b, const char* e) {
  return (e - b > 1 && b[0] == '+' && b[1] != '-') ? b + 1 : b;
}

bool to_double(std::string_view t, double& v) {
  const char* e = t.data() + t.size();
  const char* b = skip_plus(t.data(), e);
  auto r = std::from_chars(b, e, v);
  if (r.ptr != e) return false;
  if (r.ec == std::errc::result_out_of_range) {
    // from_chars leaves v untouched on overflow and underflow alike. Tell
    // them apart by a negative exponent, or no exponent and no integer part.
    std::string_view m = t.substr(t.front() == '-' || t.front() == '+');
    size_t x = m.find_first_of("eE");
    bool tiny = x != std::string_view::npos
                    ? m.substr(x + 1, 1) == "-"
                    : m.substr(0, m.find('.')).find_first_not_of('0') == std::string_view::npos;
    v = tiny ? 0.0 : HUGE_VAL;
    if (t.front() == '-') v = -v;
    return true;
  }
  return r.ec == std::errc();
}

bool to_int(std::string_view t, long long& v) {
  const char* e = t.data() + t.size();
  auto r = std::from_chars(skip_plus(t.data(), e), e, v);
  return r.ec == std::errc() && r.ptr == e;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Text formats: refuse binary data early, and drop a UTF-8 byte order mark
// some Windows editors add.
std::string_view text_of(const std::string& path, const std::string& data) {
  if (std::memchr(data.data(), '\0', data.size())) fail(path, "is not a text file (it contains NUL bytes)");
  std::string_view text(data);
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  return text;
}

// Counts from a header must fit an int (our index type) and the bytes left:
// min_bytes is the least each entry can take.
void check_count(const std::string& path, long line, long long count, const std::string& what,
                 double min_bytes, double& bytes_left) {
  if (count < 0 || count > INT_MAX)
    fail_at(path, line,
            "the header announces " + std::to_string(count) + " " + what + ", which is not a usable count");
  if (count * min_bytes > bytes_left)
    fail_at(path, line,
            "the header announces " + std::to_string(count) + " " + what +
                ", more than the rest of the file can hold (truncated file?)");
  bytes_left -= count * min_bytes;
}

// ---------------------------------------------------------------- OFF

PolygonMesh read_off(const std::string& path, std::string_view text) {
  Lines lines(text, true);
  std::string_view line;
  if (!lines.next(line)) fail(path, "is empty, expected an OFF header");
  Tokens tokens(line);
  std::string_view word;
  tokens.next(word);

  // Geomview's [ST][C][N][4][n]OFF. ST, C and N only add values after x y z
  // on each vertex line (texture coordinates, colour, normal); we skip them.
  std::string_view kind = word;
  auto drop = [&kind](std::string_view prefix) {
    if (kind.substr(0, prefix.size()) != prefix) return false;
    kind.remove_prefix(prefix.size());
    return true;
  };
  drop("ST");
  drop("C");
  drop("N");
  bool four = drop("4");
  bool n_dim = drop("n");
  if (kind != "OFF") fail_at(path, lines.number(), "expected an OFF header, got " + quoted(word));
  if (four) fail_at(path, lines.number(), "4D OFF files are not supported, only 3D ones");

  // The counts may follow OFF on its line or come on the next ones.
  auto header_int = [&](const char* what) {
    std::string_view t;
    while (!tokens.next(t)) {
      if (!lines.next(line)) fail_at(path, lines.number(), std::string("file ends before the ") + what);
      tokens = Tokens(line);
    }
    if (t == "BINARY") fail_at(path, lines.number(), "binary OFF files are not supported");
    long long v;
    if (!to_int(t, v))
      fail_at(path, lines.number(), std::string("expected the ") + what + ", got " + quoted(t));
    return v;
  };
  if (n_dim && header_int("dimension") != 3)
    fail_at(path, lines.number(), "only 3D nOFF files are supported");
  long long nv = header_int("vertex count");
  long long nf = header_int("face count");
  // The edge count, if any, is often wrong in real files and never needed.

  // A vertex takes at least "0 0 0\n", a face "3 0 0 0\n".
  double bytes_left = lines.remaining() + 1.0;
  check_count(path, lines.number(), nv, "vertices", 6, bytes_left);
  check_count(path, lines.number(), nf, "faces", 8, bytes_left);

  PolygonMesh mesh;
  mesh.vertices.resize(nv, 3);
  std::string_view t;
  for (long long i = 0; i < nv; ++i) {
    if (!lines.next(line))
      fail_at(path, lines.number(),
              "file ends after " + std::to_string(i) + " of the " + std::to_string(nv) +
                  " vertices the header announces");
    Tokens vt(line);
    for (int c = 0; c < 3; ++c) {
      if (!vt.next(t)) fail_at(path, lines.number(), "expected 3 coordinates, got " + std::to_string(c));
      double& x = mesh.vertices(i, c);
      if (!to_double(t, x)) fail_at(path, lines.number(), "expected a number, got " + quoted(t));
      if (!std::isfinite(x))
        fail_at(path, lines.number(),
                "vertex " + std::to_string(i) + " has a non-finite coordinate " + quoted(t));
    }
  }

  PolygonFaces& faces = mesh.faces;
  faces.offsets.reserve(nf + 1);
  faces.indices.reserve(std::min<size_t>(3 * nf, lines.remaining() / 2));
  for (long long f = 0; f < nf; ++f) {
    if (!lines.next(line))
      fail_at(path, lines.number(),
              "file ends after " + std::to_string(f) + " of the " + std::to_string(nf) +
                  " faces the header announces");
    Tokens ft(line);
    long long k = 0;
    ft.next(t);
    if (!to_int(t, k)) fail_at(path, lines.number(), "expected a face's vertex count, got " + quoted(t));
    if (k < 3)
      fail_at(
          path, lines.number(),
          "face " + std::to_string(f) + " has " + std::to_string(k) + " vertices, a face needs at least 3");
    for (long long j = 0; j < k; ++j) {
      long long v;
      if (!ft.next(t))
        fail_at(path, lines.number(),
                "face " + std::to_string(f) + " should list " + std::to_string(k) + " vertex indices, got " +
                    std::to_string(j));
      if (!to_int(t, v)) fail_at(path, lines.number(), "expected a vertex index, got " + quoted(t));
      if (v < 0 || v >= nv)
        fail_at(path, lines.number(),
                "face " + std::to_string(f) + " uses vertex " + std::to_string(v) + ", but there are only " +
                    std::to_string(nv) + " vertices (numbered from 0)");
      faces.indices.push_back(static_cast<int>(v));
    }
    // Anything after the indices is a per-face colour: ignored.
    faces.offsets.push_back(static_cast<int>(faces.indices.size()));
  }
  if (lines.next(line))
    fail_at(path, lines.number(),
            "data continues after the " + std::to_string(nf) + " faces the header announces");
  return mesh;
}

// ---------------------------------------------------------------- OBJ

PolygonMesh read_obj(const std::string& path, std::string_view text) {
  Lines lines(text, true);
  std::vector<double> xyz;
  PolygonFaces faces;
  std::string_view line, word, t;
  // Positive indices may point ahead (some writers put faces first), so they
  // are checked at the end against the largest one seen.
  long long largest = -1;
  long largest_line = 0;
  while (lines.next(line)) {
    Tokens tokens(line);
    tokens.next(word);
    if (word == "v") {
      // x y z, then an optional w or r g b, which we ignore.
      for (int c = 0; c < 3; ++c) {
        double x;
        if (!tokens.next(t))
          fail_at(path, lines.number(), "expected 3 coordinates, got " + std::to_string(c));
        if (!to_double(t, x)) fail_at(path, lines.number(), "expected a number, got " + quoted(t));
        if (!std::isfinite(x))
          fail_at(path, lines.number(),
                  "vertex " + std::to_string(xyz.size() / 3) + " has a non-finite coordinate " + quoted(t));
        xyz.push_back(x);
      }
    } else if (word == "f") {
      long long count = static_cast<long long>(xyz.size() / 3);
      int n = 0;
      while (tokens.next(t)) {
        // i, i/t, i//n or i/t/n: only the position index matters here.
        long long v;
        if (!to_int(t.substr(0, t.find('/')), v))
          fail_at(path, lines.number(),
                  "expected a vertex index like 7, 7/2, 7//3 or 7/2/3, got " + quoted(t));
        if (v == 0) fail_at(path, lines.number(), "vertex index 0 is invalid, OBJ indices start at 1");
        if (v < 0) {
          v += count;  // -1 is the latest vertex
          if (v < 0)
            fail_at(path, lines.number(),
                    "relative index " + quoted(t) + " reaches before the first vertex (" +
                        std::to_string(count) + " so far)");
        } else {
          if (v > INT_MAX) fail_at(path, lines.number(), "vertex index " + quoted(t) + " is too large");
          if (--v > largest) {
            largest = v;
            largest_line = lines.number();
          }
        }
        faces.indices.push_back(static_cast<int>(v));
        ++n;
      }
      if (n < 3)
        fail_at(path, lines.number(), "face has " + std::to_string(n) + " vertices, a face needs at least 3");
      faces.offsets.push_back(static_cast<int>(faces.indices.size()));
    }
    // vt, vn, g, o, s, usemtl, mtllib, l, p and any other statement do not
    // change the surface.
  }
  long long nv = static_cast<long long>(xyz.size() / 3);
  if (largest >= nv)
    fail_at(path, largest_line,
            "face uses vertex " + std::to_string(largest + 1) + ", but the file has only " +
                std::to_string(nv) + " vertices");
  PolygonMesh mesh;
  mesh.vertices = Eigen::Map<const Vertices>(xyz.data(), nv, 3);
  mesh.faces = std::move(faces);
  return mesh;
}

// ---------------------------------------------------------------- PLY

enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };

bool ply_type(std::string_view name, PlyType& t) {
  static const std::pair<const char*, PlyType> names[] = {
      {"char", PlyType::i8},    {"int8", PlyType::i8},     {"uchar", PlyType::u8},
      {"uint8", PlyType::u8},   {"short", PlyType::i16},   {"int16", PlyType::i16},
      {"ushort", PlyType::u16}, {"uint16", PlyType::u16},  {"int", PlyType::i32},
      {"int32", PlyType::i32},  {"uint", PlyType::u32},    {"uint32", PlyType::u32},
      {"float", PlyType::f32},  {"float32", PlyType::f32}, {"double", PlyType::f64},
      {"float64", PlyType::f64}};
  for (const auto& [n, type] : names)
    if (name == n) {
      t = type;
      return true;
    }
  return false;
}

size_t ply_size(PlyType t) {
  switch (t) {
    case PlyType::i8:
    case PlyType::u8:
      return 1;
    case PlyType::i16:
    case PlyType::u16:
      return 2;
    case PlyType::i32:
    case PlyType::u32:
    case PlyType::f32:
      return 4;
    case PlyType::f64:
      return 8;
  }
  return 1;
}

bool ply_integral(PlyType t) { return t != PlyType::f32 && t != PlyType::f64; }

template <class T>
T load(const char* p, bool swap) {
  char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

// A PLY value of type t as R. Integer reads only meet integer types (the
// header check makes sure).
template <class R>
R load_as(const char* p, PlyType t, bool swap) {
  switch (t) {
    case PlyType::i8:
      return static_cast<R>(load<int8_t>(p, swap));
    case PlyType::u8:
      return static_cast<R>(load<uint8_t>(p, swap));
    case PlyType::i16:
      return static_cast<R>(load<int16_t>(p, swap));
    case PlyType::u16:
      return static_cast<R>(load<uint16_t>(p, swap));
    case PlyType::i32:
      return static_cast<R>(load<int32_t>(p, swap));
    case PlyType::u32:
      return static_cast<R>(load<uint32_t>(p, swap));
    case PlyType::f32:
      return static_cast<R>(load<float>(p, swap));
    case PlyType::f64:
      return static_cast<R>(load<double>(p, swap));
  }
  return R{};
}

enum PlyRole { kSkip = -1, kX = 0, kY = 1, kZ = 2, kFaceList = 3 };

struct PlyProperty {
  std::string name;
  bool list = false;
  PlyType count_type = PlyType::u8;
  PlyType type = PlyType::f32;
  int role = kSkip;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  long line = 0;
  std::vector<PlyProperty> properties;
};

// Reads the lines up to end_header; returns the offset where data starts.
size_t read_ply_header(const std::string& path, std::string_view text, std::string& format,
                       std::vector<PlyElement>& elements, long& line_count) {
  size_t pos = 0;
  long number = 0;
  auto next = [&](std::string_view& line) {
    if (pos >= text.size()) return false;
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    line = text.substr(pos, end - pos);
    pos = end + 1;
    ++number;
    return true;
  };
  std::string_view line, word, t;
  if (next(line)) Tokens(line).next(word);
  if (word != "ply") fail(path, "is not a PLY file (it does not start with 'ply')");
  for (;;) {
    if (!next(line)) fail(path, "has no end_header line (truncated, or not a PLY file)");
    Tokens tokens(line);
    if (!tokens.next(word)) continue;
    if (word == "end_header") break;
    if (word == "comment" || word == "obj_info") continue;
    if (word == "format") {
      tokens.next(t);
      if (t != "ascii" && t != "binary_little_endian" && t != "binary_big_endian")
        fail_at(path, number,
                "unknown PLY format " + quoted(t) +
                    " (expected ascii, binary_little_endian or binary_big_endian)");
      format = t;
    } else if (word == "element") {
      PlyElement e;
      e.line = number;
      tokens.next(t);
      e.name = t;
      tokens.next(t);
      if (e.name.empty() || !to_int(t, e.count) || e.count < 0)
        fail_at(path, number, "expected 'element <name> <count>', got " + quoted(line));
      elements.push_back(std::move(e));
    } else if (word == "property") {
      if (elements.empty()) fail_at(path, number, "property comes before any element");
      PlyProperty p;
      std::string_view type, name;
      tokens.next(type);
      if (type == "list") {
        std::string_view count_type;
        tokens.next(count_type);
        tokens.next(type);
        p.list = true;
        if (!ply_type(count_type, p.count_type) || !ply_integral(p.count_type))
          fail_at(path, number, "a list length needs an integer type, got " + quoted(count_type));
      }
      if (!ply_type(type, p.type)) fail_at(path, number, "unknown property type " + quoted(type));
      if (!tokens.next(name)) fail_at(path, number, "property has no name");
      p.name = name;
      elements.back().properties.push_back(std::move(p));
    } else {
      fail_at(path, number, "unexpected header line " + quoted(line));
    }
  }
  if (format.empty()) fail(path, "the PLY header has no format line");
  line_count = number;
  return std::min(pos, text.size());
}

PolygonMesh read_ply(const std::string& path, const std::string& data) {
  std::string format;
  std::vector<PlyElement> elements;
  long header_lines = 0;
  size_t start = read_ply_header(path, data, format, elements, header_lines);
  bool ascii = format == "ascii";

  // Find what we read: x, y, z of "vertex" and the index list of "face".
  PlyElement* vertex = nullptr;
  PlyElement* face = nullptr;
  for (PlyElement& e : elements) {
    if (e.name == "vertex" || e.name == "face") {
      PlyElement*& slot = e.name == "vertex" ? vertex : face;
      if (slot) fail_at(path, e.line, "second '" + e.name + "' element");
      slot = &e;
    }
  }
  if (!vertex) fail(path, "the PLY header has no vertex element");
  for (int axis = kX; axis <= kZ; ++axis) {
    const char* name = axis == kX ? "x" : axis == kY ? "y" : "z";
    auto p = std::find_if(vertex->properties.begin(), vertex->properties.end(),
                          [&](const PlyProperty& q) { return q.name == name; });
    if (p == vertex->properties.end() || p->list)
      fail_at(path, vertex->line, std::string("the vertex element has no property ") + name);
    p->role = axis;
  }
  if (face) {
    auto p = std::find_if(face->properties.begin(), face->properties.end(), [](const PlyProperty& q) {
      return q.name == "vertex_indices" || q.name == "vertex_index";
    });
    if (p == face->properties.end() || !p->list)
      fail_at(path, face->line, "the face element has no list property vertex_indices or vertex_index");
    if (!ply_integral(p->type)) fail_at(path, face->line, "face vertex indices must have an integer type");
    p->role = kFaceList;
  }

  // Least bytes per entry: every value and list length takes its size in
  // binary, and at least one character and a separator in text.
  double bytes_left = data.size() - start + 1.0;
  for (const PlyElement& e : elements) {
    double least = 0;
    for (const PlyProperty& p : e.properties) least += ascii ? 2 : ply_size(p.list ? p.count_type : p.type);
    check_count(path, e.line, e.count, "'" + e.name + "' entries", least, bytes_left);
  }

  PolygonMesh mesh;
  long long nv = vertex->count;
  mesh.vertices.resize(nv, 3);
  PolygonFaces& faces = mesh.faces;
  if (face) {
    faces.offsets.reserve(face->count + 1);
    faces.indices.reserve(std::min<size_t>(3 * face->count, (data.size() - start) / 2));
  }
  // "vertex 12", for messages.
  auto name_of = [](const PlyElement& e, long long i) { return e.name + " " + std::to_string(i); };
  auto check_vertex = [&](long long v, const PlyElement& e, long long i, long line) {
    if (v < 0 || v >= nv) {
      std::string msg = name_of(e, i) + " uses vertex " + std::to_string(v) + ", but there are only " +
                        std::to_string(nv) + " vertices (numbered from 0)";
      ascii ? fail_at(path, line, msg) : fail(path, msg);
    }
  };
  auto check_size = [&](long long n, const PlyElement& e, long long i, long line) {
    if (n < 3) {
      std::string msg = name_of(e, i) + " has " + std::to_string(n) + " vertices, a face needs at least 3";
      ascii ? fail_at(path, line, msg) : fail(path, msg);
    }
  };

  if (ascii) {
    Lines lines(std::string_view(data).substr(start), false, header_lines + 1);
    std::string_view line, t;
    for (const PlyElement& e : elements) {
      if (e.properties.empty()) continue;
      for (long long i = 0; i < e.count; ++i) {
        if (!lines.next(line))
          fail_at(path, lines.number(),
                  "file ends after " + std::to_string(i) + " of the " + std::to_string(e.count) + " '" +
                      e.name + "' entries the header announces");
        Tokens tokens(line);
        auto value = [&]() {
          if (!tokens.next(t))
            fail_at(path, lines.number(),
                    name_of(e, i) + " has fewer values than the header's properties need");
          return t;
        };
        auto integer = [&]() {
          long long v;
          if (!to_int(value(), v)) fail_at(path, lines.number(), "expected an integer, got " + quoted(t));
          return v;
        };
        for (const PlyProperty& p : e.properties) {
          if (!p.list) {
            value();
            if (p.role == kSkip) continue;
            double& x = mesh.vertices(i, p.role);
            if (!to_double(t, x)) fail_at(path, lines.number(), "expected a number, got " + quoted(t));
            if (!std::isfinite(x))
              fail_at(path, lines.number(),
                      "vertex " + std::to_string(i) + " has a non-finite coordinate " + quoted(t));
            continue;
          }
          long long n = integer();
          if (n < 0) fail_at(path, lines.number(), "negative list length " + std::to_string(n));
          if (p.role == kFaceList) {
            check_size(n, e, i, lines.number());
            for (long long j = 0; j < n; ++j) {
              long long v = integer();
              check_vertex(v, e, i, lines.number());
              faces.indices.push_back(static_cast<int>(v));
            }
            faces.offsets.push_back(static_cast<int>(faces.indices.size()));
          } else {
            for (long long j = 0; j < n; ++j) value();
          }
        }
        if (!tokens.empty())
          fail_at(path, lines.number(),
                  name_of(e, i) + " has more values than the header's properties describe");
      }
    }
    if (lines.next(line))
      fail_at(path, lines.number(), "data continues after the last element the header announces");
    return mesh;
  }

  const uint16_t one = 1;
  bool host_big = *reinterpret_cast<const unsigned char*>(&one) == 0;
  bool swap = (format == "binary_big_endian") != host_big;
  const char* p = data.data() + start;
  const char* end = data.data() + data.size();
  auto truncated = [&](const PlyElement& e, long long i) {
    fail(path, "file ends inside " + name_of(e, i) + " of " + std::to_string(e.count) + " (truncated file?)");
  };
  for (const PlyElement& e : elements) {
    bool fixed = std::none_of(e.properties.begin(), e.properties.end(), [](auto& q) { return q.list; });
    if (fixed && &e != vertex) {
      // Nothing to read: jump over it (check_count made sure it fits).
      size_t record = 0;
      for (const PlyProperty& q : e.properties) record += ply_size(q.type);
      if (static_cast<size_t>(end - p) < record * e.count) truncated(e, e.count - 1);
      p += record * e.count;
      continue;
    }
    for (long long i = 0; i < e.count; ++i) {
      for (const PlyProperty& q : e.properties) {
        if (!q.list) {
          size_t size = ply_size(q.type);
          if (static_cast<size_t>(end - p) < size) truncated(e, i);
          if (q.role != kSkip) {
            double x = load_as<double>(p, q.type, swap);
            if (!std::isfinite(x)) fail(path, "vertex " + std::to_string(i) + " has a non-finite coordinate");
            mesh.vertices(i, q.role) = x;
          }
          p += size;
          continue;
        }
        size_t count_size = ply_size(q.count_type), size = ply_size(q.type);
        if (static_cast<size_t>(end - p) < count_size) truncated(e, i);
        long long n = load_as<long long>(p, q.count_type, swap);
        p += count_size;
        if (n < 0) fail(path, name_of(e, i) + " has a negative list length " + std::to_string(n));
        if (static_cast<size_t>(end - p) / size < static_cast<size_t>(n)) truncated(e, i);
        if (q.role == kFaceList) {
          check_size(n, e, i, 0);
          for (long long j = 0; j < n; ++j) {
            long long v = load_as<long long>(p + j * size, q.type, swap);
            check_vertex(v, e, i, 0);
            faces.indices.push_back(static_cast<int>(v));
          }
          faces.offsets.push_back(static_cast<int>(faces.indices.size()));
        }
        p += n * size;
      }
    }
  }
  // Bytes after the last element are tolerated: some writers pad.
  return mesh;
}

}  // namespace

void check_path(const std::string& path) {
  if (path.find('\0') == std::string::npos) return;
  std::string shown = path;
  for (char& c : shown)
    if (c == '\0') c = '?';
  throw Error("the path '" + shown + "' contains a NUL character, which no file name can hold");
}

std::string read_file(const std::string& path) {
  check_path(path);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory, not a file");
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::unique_ptr<std::FILE, Closer> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw Error("cannot open " + path + ": " + std::strerror(errno));
  std::string data;
  auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > 0) {
    data.resize(size);
    data.resize(std::fread(data.data(), 1, size, file.get()));
  }
  // Also catches files that grow while we read, and sizes the filesystem
  // does not report (pipes, /proc).
  char chunk[65536];
  while (size_t n = std::fread(chunk, 1, sizeof chunk, file.get())) data.append(chunk, n);
  if (std::ferror(file.get())) throw Error("cannot read " + path + ": " + std::strerror(errno));
  return data;
}

PolygonMesh read_mesh(const std::string& path) {
  check_path(path);
  std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext != ".off" && ext != ".obj" && ext != ".ply")
    fail(path, ext.empty() ? "has no file extension, expected .off, .obj or .ply"
                           : "unknown mesh format '" + ext + "', expected .off, .obj or .ply");
  return parse_mesh(path, read_file(path));
}

PolygonMesh parse_mesh(const std::string& name, const std::string& data) {
  const std::string ext = lower(std::filesystem::path(name).extension().string());
  PolygonMesh mesh;
  if (ext == ".ply") mesh = read_ply(name, data);
  else if (ext == ".off") mesh = read_off(name, text_of(name, data));
  else if (ext == ".obj") mesh = read_obj(name, text_of(name, data));
  else fail(name, "unknown mesh format '" + ext + "', expected .off, .obj or .ply");
  // The readers grow the face lists as they read (up to twice the size); the
  // mesh lives as long as the program.
  mesh.faces.indices.shrink_to_fit();
  mesh.faces.offsets.shrink_to_fit();
  return mesh;
}

}  // namespace polycube
