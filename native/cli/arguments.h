// A small command-line parser: positional inputs (one, or as many as the command takes) and `--name value` options
// (or `--flag`), each checked against what the command accepts, so a typo is
// an error rather than silently ignored.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace polycube {

class Arguments {
 public:
  // args: everything after the command name. Throws Error on an unknown
  // option, a missing value, a repeated option or a wrong number of inputs.
  Arguments(const std::vector<std::string>& args, const std::set<std::string>& options_with_value,
            const std::set<std::string>& flags = {}, size_t input_count = 1);

  const std::string& input(size_t k = 0) const { return inputs_.at(k); }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::string get(const std::string& name, const std::string& fallback) const;
  int get_int(const std::string& name, int fallback, int minimum) const;
  double get_double(const std::string& name, double fallback, double minimum) const;

 private:
  std::vector<std::string> inputs_;
  std::map<std::string, std::string> values_;
};

}  // namespace polycube
