// Standard output is a result like any file: when it cannot be written (a
// full disk, a closed pipe, > /dev/full) the command fails instead of
// exiting 0 with the report lost.
#pragma once

#include <string_view>

namespace polycube {

// Writes text and a newline to stdout; throws Error saying why when the write
// fails (a report longer than stdout's buffer fails here, while errno still
// says why).
void print_line(std::string_view text);

// Flushes stdout; throws Error saying why when it or an earlier write failed.
// Commands call it before committing their files (output_files.h), so a
// lost report leaves no files either; main calls it once more at the end.
void flush_stdout();

}  // namespace polycube
