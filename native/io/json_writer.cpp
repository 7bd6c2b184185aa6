// JsonWriter keeps a small tree and formats it only in str(), so the caller
// chooses the indentation at the end and may add to a report in any order
// its phases finish.
#include "io/json_writer.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace polycube {

struct JsonWriter::Node {
  enum Kind { kValue, kObject, kArray, kInts } kind = kValue;
  std::string text;               // kValue: the JSON text of a scalar
  std::vector<std::string> keys;  // kObject: parallel to children
  std::vector<Node> children;     // kObject, kArray
  std::vector<int> ints;          // kInts: kept compact, face arrays can be long
};

namespace {

using Node = JsonWriter::Node;

std::string quote(std::string_view s) {
  std::string out = "\"";
  for (size_t i = 0; i < s.size(); ++i) {
    unsigned char c = s[i];
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c < 0x20) {
      const char* named = c == '\n' ? "\\n" : c == '\t' ? "\\t" : c == '\r' ? "\\r" : nullptr;
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += named ? named : buf;
    } else if (c < 0x80) {
      out += c;
    } else {
      // UTF-8 passes through; a byte that starts no valid sequence (a Latin-1
      // path, say) becomes U+FFFD so the report stays valid JSON.
      size_t n = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
      bool ok = n && i + n <= s.size();
      for (size_t k = 1; ok && k < n; ++k) ok = (static_cast<unsigned char>(s[i + k]) & 0xC0) == 0x80;
      if (ok) {
        out.append(s.substr(i, n));
        i += n - 1;
      } else {
        out += "\xEF\xBF\xBD";
      }
    }
  }
  return out + '"';
}

Node value(std::string text) {
  Node n;
  n.text = std::move(text);
  return n;
}

Node number(double x) {
  if (!std::isfinite(x)) return value("null");
  char buf[32];
  std::string s(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
  // Keep it a float for readers that care (Python's json): 2 -> 2.0.
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return value(s);
}

Node container(Node::Kind kind) {
  Node n;
  n.kind = kind;
  return n;
}

void write(const Node& n, int indent, int depth, std::string& out) {
  const char* comma = indent > 0 ? ", " : ",";
  if (n.kind == Node::kValue) {
    out += n.text;
  } else if (n.kind == Node::kInts) {
    out += '[';
    for (size_t i = 0; i < n.ints.size(); ++i) {
      if (i) out += comma;
      out += std::to_string(n.ints[i]);
    }
    out += ']';
  } else {
    bool object = n.kind == Node::kObject;
    // Arrays of plain values stay on one line; anything else nests.
    bool flat = indent <= 0 || n.children.empty();
    if (!flat && !object)
      flat = std::none_of(n.children.begin(), n.children.end(),
                          [](const Node& c) { return c.kind == Node::kObject || c.kind == Node::kArray; });
    out += object ? '{' : '[';
    for (size_t i = 0; i < n.children.size(); ++i) {
      if (!flat)
        out.append(i ? ",\n" : "\n").append((depth + 1) * indent, ' ');
      else if (i)
        out += comma;
      if (object) out.append(quote(n.keys[i])).append(indent > 0 ? ": " : ":");
      write(n.children[i], indent, depth + 1, out);
    }
    if (!flat) out.append("\n").append(depth * indent, ' ');
    out += object ? '}' : ']';
  }
}

}  // namespace

JsonWriter::JsonWriter() : root_(std::make_unique<Node>(container(Node::kObject))), open_{root_.get()} {}
JsonWriter::~JsonWriter() = default;
JsonWriter::JsonWriter(JsonWriter&&) noexcept = default;
JsonWriter& JsonWriter::operator=(JsonWriter&&) noexcept = default;

JsonWriter& JsonWriter::insert(const std::string_view* key, Node node) {
  Node& parent = *open_.back();
  if ((parent.kind == Node::kObject) != (key != nullptr))
    throw std::logic_error(key ? "JsonWriter: a key inside an array"
                               : "JsonWriter: a value without a key in an object");
  if (key) parent.keys.emplace_back(*key);
  parent.children.push_back(std::move(node));
  if (parent.children.back().kind == Node::kObject || parent.children.back().kind == Node::kArray)
    open_.push_back(&parent.children.back());
  return *this;
}

JsonWriter& JsonWriter::add_number(const std::string_view* key, std::string text) {
  return insert(key, value(std::move(text)));
}

JsonWriter& JsonWriter::add(std::string_view key, std::string_view v) {
  return insert(&key, value(quote(v)));
}
JsonWriter& JsonWriter::add(std::string_view key, bool v) {
  return insert(&key, value(v ? "true" : "false"));
}
JsonWriter& JsonWriter::add(std::string_view key, double v) { return insert(&key, number(v)); }
JsonWriter& JsonWriter::add(std::string_view key, const std::vector<int>& v) {
  Node n = container(Node::kInts);
  n.ints = v;
  return insert(&key, std::move(n));
}
JsonWriter& JsonWriter::begin_object(std::string_view key) { return insert(&key, container(Node::kObject)); }
JsonWriter& JsonWriter::begin_array(std::string_view key) { return insert(&key, container(Node::kArray)); }

JsonWriter& JsonWriter::push(std::string_view v) { return insert(nullptr, value(quote(v))); }
JsonWriter& JsonWriter::push(bool v) { return insert(nullptr, value(v ? "true" : "false")); }
JsonWriter& JsonWriter::push(double v) { return insert(nullptr, number(v)); }
JsonWriter& JsonWriter::begin_object() { return insert(nullptr, container(Node::kObject)); }
JsonWriter& JsonWriter::begin_array() { return insert(nullptr, container(Node::kArray)); }

JsonWriter& JsonWriter::end() {
  if (open_.size() <= 1) throw std::logic_error("JsonWriter: end() without an open object or array");
  open_.pop_back();
  return *this;
}

std::string JsonWriter::str(int indent) const {
  std::string out;
  write(*root_, indent, 0, out);
  return out;
}

}  // namespace polycube
