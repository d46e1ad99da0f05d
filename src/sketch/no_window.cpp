// SPDX-License-Identifier: MIT
// calder::sketch built without SDL2: headless only.
#include "calder/error.hpp"
#include "runner.hpp"

namespace calder {

std::string sketch_no_display_reason() {
  return "this calder::sketch was built without a window (SDL2)";
}

bool sketch_has_window() { return false; }

void run_sketch_window(SketchRunner& /*runner*/) { throw InputError(sketch_no_display_reason()); }

}  // namespace calder
