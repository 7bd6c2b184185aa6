// The subcommands of the `polycube` program. Each takes the arguments after its
// name, returns the exit code, and throws Error for anything the user must fix.
#pragma once

#include <string>
#include <vector>

namespace polycube {

extern const char* const kDeformUsage;
int deform_command(const std::vector<std::string>& args);
extern const char* const kLabelUsage;
int label_command(const std::vector<std::string>& args);
extern const char* const kValidateUsage;
int validate_command(const std::vector<std::string>& args);
extern const char* const kRefineUsage;
int refine_command(const std::vector<std::string>& args);
extern const char* const kUvUsage;
int uv_command(const std::vector<std::string>& args);
extern const char* const kRemeshUsage;
int remesh_command(const std::vector<std::string>& args);

}  // namespace polycube
