#pragma once
// Long work (a render, a sequence score) runs on a worker thread while the calling thread,
// which holds the interpreter, waits without the GIL and checks every 50 ms for a signal:
// other Python threads run meanwhile, and Ctrl-C sets `cancel`, which the work honours at its
// next safe point (a reference pass, a real-time frame), then raises KeyboardInterrupt.
// `poll` runs on the calling thread with the GIL at each check (progress callbacks), and
// may raise.

#include <pybind11/pybind11.h>

#include <atomic>
#include <functional>

namespace giq::python {

// Thrown by work that stopped because cancel was set.
struct Cancelled {};

void run_interruptible(const std::function<void(const std::atomic<bool>& cancel)>& work,
                       const std::function<void()>& poll = {});

}  // namespace giq::python
