// A small command-line parser: one positional input and `--name value` options
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
            const std::set<std::string>& flags = {});

  const std::string& input() const { return input_; }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::string get(const std::string& name, const std::string& fallback) const;
  int get_int(const std::string& name, int fallback, int minimum) const;
  double get_double(const std::string& name, double fallback, double minimum) const;

 private:
  std::string input_;
  std::map<std::string, std::string> values_;
};

}  // namespace polycube
