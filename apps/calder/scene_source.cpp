// SPDX-License-Identifier: MIT
#include "scene_source.hpp"

#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "calder/error.hpp"
#include "errors.hpp"

#if CALDER_APP_HAS_SCENE_FILE
#include "calder/scene_file.hpp"
#endif

namespace calder::app {

namespace {

// The .toml files of the current folder (at most the first 1000 entries looked at).
std::vector<std::string> scene_files_here() {
  std::vector<std::string> files;
  std::error_code ec;
  std::size_t looked = 0;
  for (std::filesystem::directory_iterator it(".", ec), end; !ec && it != end && looked < 1000;
       it.increment(ec), ++looked) {
    const std::string name = it->path().filename().string();
    if (name.ends_with(".toml") && name.size() <= 64) files.push_back(name);
  }
  return files;
}

}  // namespace

bool names_scene_file(const std::string& argument) {
  std::error_code ec;
  return std::filesystem::exists(argument, ec) || argument.ends_with(".toml") ||
         argument.find('/') != std::string::npos;
}

Scene load_scene_argument(const std::string& argument) {
  if (argument.empty()) throw InputError("the scene name is empty");
  if (!names_scene_file(argument)) {
    for (const SceneInfo& info : builtin_scenes()) {
      if (info.name == argument) return builtin_scene(argument);
    }
    std::string names;
    std::vector<std::string_view> candidates;
    for (const SceneInfo& info : builtin_scenes()) {
      names += names.empty() ? "" : ", ";
      names += info.name;
      candidates.emplace_back(info.name);
    }
    std::string message = "unknown scene '" + detail::printable(argument) + "'";
    // A scene file of this folder named like it ("three" for three.toml), or
    // a built-in scene it is a typo of.
    const std::vector<std::string> files = scene_files_here();
    for (const std::string& file : files) candidates.emplace_back(file);
    if (const auto near = detail::closest(argument, candidates)) {
      message += " (did you mean '" + std::string(*near) + "'?)";
    } else if (const auto file = detail::closest(argument + ".toml", candidates)) {
      message += " (did you mean '" + std::string(*file) + "'?)";
    }
    throw InputError(message + ": not a built-in scene (" + names +
                     ") nor a scene file (a path that exists or ends in .toml)");
  }
  std::error_code ec;
  if (std::filesystem::is_directory(argument, ec)) {
    throw InputError(detail::printable(argument, 240) + ": is a directory, not a scene file");
  }
#if CALDER_APP_HAS_SCENE_FILE
  return load_scene_file(argument);
#else
  throw InputError(argument +
                   ": this calder was built without scene files (no calder::scene_file target)");
#endif
}

}  // namespace calder::app
