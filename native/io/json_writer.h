// A small JSON builder for run reports (the quality figures and timings of
// docs/design.md section 4), so the command-line program needs no JSON library.
//
//   JsonWriter json;                              // the root object is open
//   json.add("mesh", "fandisk.off").add("converged", true);
//   json.begin_object("timing").add("solve", 0.12).end();
//   json.begin_array("runs").begin_object().add("iterations", 7).end().end();
//   std::string text = json.str();
//
// Keys keep insertion order. Non-finite doubles become null (JSON has no
// NaN); finite ones are written with the shortest text that reads back
// exactly. Calls that do not fit the innermost open container (a key inside
// an array, end() with nothing open) throw std::logic_error: they are bugs
// in the caller, not bad input.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace polycube {

class JsonWriter {
 public:
  JsonWriter();
  ~JsonWriter();
  JsonWriter(JsonWriter&&) noexcept;
  JsonWriter& operator=(JsonWriter&&) noexcept;

  // Members of the innermost open object.
  JsonWriter& add(std::string_view key, std::string_view value);
  JsonWriter& add(std::string_view key, const char* value) { return add(key, std::string_view(value)); }
  JsonWriter& add(std::string_view key, bool value);
  JsonWriter& add(std::string_view key, double value);
  template <class T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>, int> = 0>
  JsonWriter& add(std::string_view key, T value) {
    return add_number(&key, std::to_string(value));
  }
  JsonWriter& add(std::string_view key, const std::vector<int>& values);
  JsonWriter& begin_object(std::string_view key);
  JsonWriter& begin_array(std::string_view key);

  // Elements of the innermost open array.
  JsonWriter& push(std::string_view value);
  JsonWriter& push(const char* value) { return push(std::string_view(value)); }
  JsonWriter& push(bool value);
  JsonWriter& push(double value);
  template <class T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>, int> = 0>
  JsonWriter& push(T value) {
    return add_number(nullptr, std::to_string(value));
  }
  JsonWriter& begin_object();
  JsonWriter& begin_array();

  // Closes the innermost open object or array.
  JsonWriter& end();

  struct Node;  // the tree behind the text; opaque

  // The document so far, containers still open included. indent <= 0 puts it
  // all on one line; arrays of plain values always stay on one line.
  std::string str(int indent = 2) const;

 private:
  JsonWriter& add_number(const std::string_view* key, std::string text);
  JsonWriter& insert(const std::string_view* key, Node node);

  std::unique_ptr<Node> root_;
  std::vector<Node*> open_;  // innermost last; ancestors do not move while a child is open
};

}  // namespace polycube
