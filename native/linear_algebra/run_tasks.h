// Independent tasks of a millisecond or more (a factorisation, a
// back-substitution, a trial step) on a few threads that sleep between
// them. OpenMP's threads spin after each parallel region instead (libgomp:
// for milliseconds), and on two cores a spinning thread takes the core a
// task needs: B0's polish ran its trials side by side no faster than one
// after the other until its solves left OpenMP (docs/design.md section
// 2.6, "Cost").
#pragma once

#include <functional>

namespace polycube {

// Calls task(0) .. task(count - 1), each once, on the calling thread and on
// up to task_threads(count) - 1 others (parallel.h), taking the tasks in
// order as threads come free; returns when all are done. Called from within
// a task, or while another thread's tasks run, the tasks run one after the
// other on the calling thread. The first exception a task throws is thrown
// here once every task has ended.
void run_tasks(int count, const std::function<void(int)>& task);

// body(begin, end) over [0, count) in `parts` contiguous ranges of nearly
// equal size, each a task of run_tasks().
template <class Body>
void run_in_parts(long count, int parts, const Body& body) {
  if (parts <= 1) return body(0L, count);
  run_tasks(parts, [&](int part) { body(count * part / parts, count * (part + 1) / parts); });
}

}  // namespace polycube
