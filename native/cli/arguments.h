// The command line of one `polycube` command through CLI11 (Debian
// libcli11-dev): the command declares its inputs and options on a CLI::App,
// bound to its variables and with their help; parse_arguments parses them and
// turns CLI11's failures into the one-sentence errors every command gives, so
// a typo is an error rather than silently ignored.
//
//   CLI::App app{"Deforms the mesh into its polycube.", "polycube deform"};
//   std::string input;
//   int iterations = 100;
//   app.add_option("IN", input, "the mesh")->required();
//   app.add_option("--iterations", iterations, "iteration limit")->check(whole_number_at_least(0));
//   if (!parse_arguments(app, args)) return 0;   // --help was printed
#pragma once

#include <string>
#include <vector>

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>

namespace polycube {

// Checks on an option's text, refused with a sentence naming the value.
CLI::Validator whole_number_at_least(int minimum);
CLI::Validator number_at_least(double minimum);  // finite

// Parses args (everything after the command's name) into app's options.
// Returns false when --help or -h was given: app's help is then on stdout.
// Throws Error on an unknown option, a missing or repeated value, a value a
// check refuses, a missing required option, or a wrong number of inputs
// (app's positional options).
bool parse_arguments(CLI::App& app, const std::vector<std::string>& args);

}  // namespace polycube
