#include "cli/arguments.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "cli/flush_stdout.h"
#include "mesh/mesh.h"

namespace polycube {
namespace {

// Non-empty when text is not a number of type T at least minimum.
template <class T>
std::string refuse_below(const std::string& text, T minimum, const std::string& what) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc() && end == text.data() + text.size() && std::isfinite(static_cast<double>(value)) &&
      value >= minimum)
    return {};
  return "must be " + what + ", got '" + text + "'";
}

bool looks_like_option(const std::string& arg) {
  double number = 0;
  const auto [end, error] = std::from_chars(arg.data(), arg.data() + arg.size(), number);
  return arg.size() > 1 && arg[0] == '-' && !(error == std::errc() && end == arg.data() + arg.size());
}

// The inputs' sentences: none, too few, one too many.
[[noreturn]] void wrong_inputs(size_t expected, size_t given, const std::string& extra) {
  if (given == 0) throw Error("no input mesh given");
  if (given < expected)
    throw Error("expected " + std::to_string(expected) + " inputs, got " + std::to_string(given));
  throw Error((expected == 1 ? std::string("more than one input") : "more than " + std::to_string(expected) + " inputs") +
              " given: '" + extra + "'");
}

}  // namespace

CLI::Validator whole_number_at_least(int minimum) {
  const std::string bound = std::to_string(minimum);
  return CLI::Validator(
      [=](std::string& text) { return refuse_below<int>(text, minimum, "a whole number of at least " + bound); },
      "");
}

CLI::Validator number_at_least(double minimum) {
  char bound[32];
  std::snprintf(bound, sizeof bound, "%g", minimum);
  return CLI::Validator(
      [=](std::string& text) { return refuse_below<double>(text, minimum, std::string("a number of at least ") + bound); },
      "");
}

bool parse_arguments(CLI::App& app, const std::vector<std::string>& args) {
  // CLI11 would take the next option for the missing value (--iterations --output x).
  for (size_t k = 0; k < args.size(); ++k) {
    const CLI::Option* option = args[k].rfind("--", 0) == 0 ? app.get_option_no_throw(args[k]) : nullptr;
    if (option && option->get_expected_min() > 0 && (k + 1 == args.size() || args[k + 1].rfind("--", 0) == 0))
      throw Error("option " + args[k] + " needs a value");
  }
  app.allow_extras();  // unknown options and extra inputs get our sentences below
  size_t expected = 0, given = 0;
  try {
    app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 takes them last first
  } catch (const CLI::CallForHelp&) {
    // Through print_line: a help longer than stdout's buffer fails while
    // writing, and only there does errno say why.
    std::string help = app.help();
    if (!help.empty() && help.back() == '\n') help.pop_back();
    print_line(help);
    return false;
  } catch (const CLI::ArgumentMismatch& e) {
    const std::string what = e.what();
    const std::string name = what.substr(0, what.find(':'));
    throw Error("option " + name + (what.find("missing") != std::string::npos ? " needs a value" : " is given more than once"));
  } catch (const CLI::RequiredError& e) {
    for (const CLI::Option* option : app.get_options())
      if (option->get_positional()) {
        ++expected;
        given += option->count() > 0;
      }
    if (given < expected) wrong_inputs(expected, given, "");
    throw Error(e.what());
  } catch (const CLI::ParseError& e) {
    throw Error(e.what());
  }
  const std::vector<std::string> extras = app.remaining();
  for (const std::string& extra : extras)
    if (looks_like_option(extra)) throw Error("unknown option " + extra + " (see --help)");
  if (!extras.empty()) {
    for (const CLI::Option* option : app.get_options()) expected += option->get_positional();
    wrong_inputs(expected, expected + 1, extras.front());
  }
  return true;
}

}  // namespace polycube
