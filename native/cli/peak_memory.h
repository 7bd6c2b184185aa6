// The program's peak resident memory, for the report and the benchmark.
//
// Read from /proc/self/status (VmHWM) rather than getrusage: ru_maxrss also
// counts the parent's pages when the program was started with vfork, as
// Python's subprocess does, so it would report the caller's size.
#pragma once

namespace polycube {

// In MiB; 0 when /proc is not available.
double peak_resident_mib();

}  // namespace polycube
