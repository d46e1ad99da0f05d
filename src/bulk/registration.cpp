// SPDX-License-Identifier: MIT
// calder::bulk registers its kernels as the process default of
// calder/backends.hpp while the program starts, so that a world asking for
// Arithmetic::float32 (or a large book step) gets them by linking
// calder::bulk alone. CMake's calder::bulk and calder-bulk.pc link with
// --undefined=calder_bulk_linked, which keeps this object (and so its
// initialiser) in a program even when it names nothing else of calder::bulk.
#include "calder/backends.hpp"
#include "calder/bulk.hpp"

// The symbol the link option names (its value is not used).
extern "C" {
extern const char calder_bulk_linked;
const char calder_bulk_linked = 1;
}

namespace calder::bulk {
namespace {

const bool registered = [] {
  set_step_batch_backend(step_batch);
  return true;
}();

}  // namespace
}  // namespace calder::bulk
