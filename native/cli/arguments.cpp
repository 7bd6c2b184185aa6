#include "cli/arguments.h"

#include <charconv>
#include <cmath>

#include "mesh/mesh.h"

namespace polycube {

Arguments::Arguments(const std::vector<std::string>& args, const std::set<std::string>& options_with_value,
                     const std::set<std::string>& flags, size_t input_count) {
  std::vector<std::string>& inputs = inputs_;
  for (size_t k = 0; k < args.size(); ++k) {
    const std::string& arg = args[k];
    if (arg.rfind("--", 0) != 0) {
      inputs.push_back(arg);
      continue;
    }
    const std::string name = arg.substr(2);
    if (values_.count(name)) throw Error("option " + arg + " is given twice");
    if (flags.count(name)) {
      values_[name] = "1";
    } else if (options_with_value.count(name)) {
      if (k + 1 >= args.size() || args[k + 1].rfind("--", 0) == 0) throw Error("option " + arg + " needs a value");
      values_[name] = args[++k];
    } else {
      throw Error("unknown option " + arg + " (see --help)");
    }
  }
  if (inputs.size() < input_count)
    throw Error(inputs.empty() ? "no input mesh given"
                               : "expected " + std::to_string(input_count) + " inputs, got " + std::to_string(inputs.size()));
  if (inputs.size() > input_count)
    throw Error((input_count == 1 ? std::string("more than one input") : "more than " + std::to_string(input_count) + " inputs") +
                " given: '" + inputs[input_count] + "'");
}

std::string Arguments::get(const std::string& name, const std::string& fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

int Arguments::get_int(const std::string& name, int fallback, int minimum) const {
  if (!has(name)) return fallback;
  const std::string& text = values_.at(name);
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < minimum)
    throw Error("--" + name + " must be a whole number of at least " + std::to_string(minimum) + ", got '" + text + "'");
  return value;
}

double Arguments::get_double(const std::string& name, double fallback, double minimum) const {
  if (!has(name)) return fallback;
  const std::string& text = values_.at(name);
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value) || value < minimum)
    throw Error("--" + name + " must be a number of at least " + std::to_string(minimum) + ", got '" + text + "'");
  return value;
}

}  // namespace polycube
