// SPDX-License-Identifier: MIT
// The process defaults of calder/backends.hpp: the kernels of the linked
// component libraries, which register themselves while the program starts.
#include "calder/backends.hpp"

#include <atomic>

namespace calder {

namespace {

// Constant-initialised (null), so a component's registration, run during
// dynamic initialisation in whatever order, always finds them ready.
std::atomic<StepBatchBackend> default_step_batch{nullptr};
std::atomic<MutualAttractionBackend> default_mutual_attraction{nullptr};

}  // namespace

void set_step_batch_backend(StepBatchBackend backend) { default_step_batch = backend; }
void set_mutual_attraction_backend(MutualAttractionBackend backend) {
  default_mutual_attraction = backend;
}

Backends Backends::or_defaults() const {
  return {.step_batch = step_batch != nullptr ? step_batch : default_step_batch.load(),
          .mutual_attraction =
              mutual_attraction != nullptr ? mutual_attraction : default_mutual_attraction.load()};
}

}  // namespace calder
