#include "interruptible.h"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace giq::python {

namespace py = pybind11;

void run_interruptible(const std::function<void(const std::atomic<bool>& cancel)>& work,
                       const std::function<void()>& poll) {
  std::atomic<bool> cancel{false};
  std::mutex m;
  std::condition_variable done_cv;
  bool done = false;
  std::exception_ptr error;
  std::thread worker([&] {
    try {
      work(cancel);
    } catch (const Cancelled&) {
    } catch (...) {
      error = std::current_exception();
    }
    std::lock_guard lock(m);
    done = true;
    done_cv.notify_all();
  });
  // Whatever leaves this loop (a signal, a callback that raised) first stops and joins the
  // worker, which references this frame.
  std::exception_ptr raised;
  for (;;) {
    bool finished;
    {
      py::gil_scoped_release release;
      std::unique_lock lock(m);
      finished = done_cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; });
    }
    if (finished) break;
    if (raised) continue;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (poll) poll();
    } catch (...) {
      raised = std::current_exception();
      cancel = true;
    }
  }
  worker.join();
  if (raised) std::rethrow_exception(raised);
  if (error) std::rethrow_exception(error);
  if (poll) poll();
}

}  // namespace giq::python
