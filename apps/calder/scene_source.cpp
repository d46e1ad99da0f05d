// SPDX-License-Identifier: MIT
#include "scene_source.hpp"

#include <string>

#include "calder/error.hpp"

#if CALDER_APP_HAS_SCENE_FILE
#include "calder/scene_file.hpp"
#endif

namespace calder::app {

Scene load_scene_argument(const std::string& argument) {
#if CALDER_APP_HAS_SCENE_FILE
  return load_scene(argument);  // the library's rule, shared with Python
#else
  if (argument.empty()) throw InputError("the scene name is empty");
  if (is_builtin_scene(argument)) return builtin_scene(argument);
  if (argument.ends_with(".toml") || argument.find('/') != std::string::npos) {
    throw InputError(argument +
                     ": this calder was built without scene files (no calder::scene_file target)");
  }
  throw InputError(unknown_scene_message(argument));
#endif
}

}  // namespace calder::app
