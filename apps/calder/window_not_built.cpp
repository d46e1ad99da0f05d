// SPDX-License-Identifier: MIT
// `calder window` in a calder built without SDL2 (CALDER_WITH_WINDOW=OFF): the
// verb is there, takes any flags, and says why it can't run (exit 2).
#include <CLI/CLI.hpp>

#include "errors.hpp"
#include "window_command.hpp"

namespace calder::app {

CLI::App* add_window_command(CLI::App& app, WindowOptions& /*options*/) {
  CLI::App* window = app.add_subcommand(
      "window", "Run a scene in a window (not in this build: CALDER_WITH_WINDOW=OFF)");
  window->allow_extras();
  return window;
}

void window_command(const WindowOptions& /*options*/, std::ostream& /*out*/,
                    std::ostream& /*err*/) {
  throw InputError(
      "window: this calder was built without SDL2 (CALDER_WITH_WINDOW=OFF); install libsdl2-dev "
      "and configure with -DCALDER_WITH_WINDOW=ON");
}

}  // namespace calder::app
