// The subcommands of the `polycube` program. Each takes the arguments after its
// name (its options declared with CLI11, arguments.h; --help prints them),
// returns the exit code, and throws Error for anything the user must fix.
#pragma once

#include <string>
#include <vector>

namespace polycube {

int deform_command(const std::vector<std::string>& args);
int label_command(const std::vector<std::string>& args);
int validate_command(const std::vector<std::string>& args);
int refine_command(const std::vector<std::string>& args);
int uv_command(const std::vector<std::string>& args);
int remesh_command(const std::vector<std::string>& args);

}  // namespace polycube
