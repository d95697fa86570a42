// Long core calls from Python: without the GIL, with progress and cancel.
#pragma once

#include <pybind11/pybind11.h>

#include "tessella/progress.h"

namespace tessella::bindings {

namespace py = pybind11;

// Releases the GIL around long core calls.
template <class F>
auto nogil(F f) {
  py::gil_scoped_release release;
  return f();
}

// Runs a long core call without the GIL, reporting to `progress` (a Python
// callable (fraction, stage) -> bool, False cancels; None: no reporting).
template <class F>
auto with_progress(const py::object& progress, F f) {
  if (progress.is_none()) return nogil(f);
  ProgressScope scope([progress](double fraction, const char* stage) {
    py::gil_scoped_acquire gil;
    try {
      return py::bool_(progress(fraction, stage)).cast<bool>();
    } catch (py::error_already_set&) {
      return false;  // an error in the callback stops the work
    }
  });
  return nogil(f);
}

}  // namespace tessella::bindings
