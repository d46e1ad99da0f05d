// SPDX-License-Identifier: MIT
#include "scene_source.hpp"

#include <filesystem>
#include <system_error>

#include "errors.hpp"

#if CALDER_APP_HAS_SCENE_FILE
#include "calder/scene_file.hpp"
#endif

namespace calder::app {

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

bool names_scene_file(const std::string& argument) {
  std::error_code ec;
  return std::filesystem::exists(argument, ec) || ends_with(argument, ".toml") ||
         argument.find('/') != std::string::npos;
}

Scene load_scene_argument(const std::string& argument) {
  if (argument.empty()) throw InputError("the scene name is empty");
  if (!names_scene_file(argument)) {
    for (const SceneInfo& info : builtin_scenes()) {
      if (info.name == argument) return builtin_scene(argument);
    }
    std::string names;
    for (const SceneInfo& info : builtin_scenes()) {
      names += names.empty() ? "" : ", ";
      names += info.name;
    }
    throw InputError("unknown scene '" + argument + "': not a built-in scene (" + names +
                     ") nor a scene file (a path that exists or ends in .toml)");
  }
  std::error_code ec;
  if (std::filesystem::is_directory(argument, ec)) {
    throw InputError(argument + ": is a directory, not a scene file");
  }
#if CALDER_APP_HAS_SCENE_FILE
  return load_scene_file(argument);
#else
  throw InputError(argument +
                   ": this calder was built without scene files (no calder::scene_file target)");
#endif
}

}  // namespace calder::app
