// SPDX-License-Identifier: MIT
// calder scene files: a front end's scene argument, a built-in scene's name
// or a scene file's path, decided one way for the calder command and Python
// (calder/scene_file.hpp).
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "calder/error.hpp"
#include "calder/scene.hpp"
#include "calder/scene_file.hpp"

namespace calder {

namespace {

// The .toml files of the current folder (at most the first 1000 entries
// looked at): candidates for a mistyped name.
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

Scene load_scene(const std::string& name_or_path) {
  if (name_or_path.empty()) throw InputError("the scene name is empty");
  if (!names_scene_file(name_or_path)) {
    if (is_builtin_scene(name_or_path)) return builtin_scene(name_or_path);
    const std::vector<std::string> files = scene_files_here();
    const std::vector<std::string_view> also(files.begin(), files.end());
    throw InputError(unknown_scene_message(name_or_path, also) +
                     " nor a scene file (a path that exists or ends in .toml)");
  }
  std::error_code ec;
  if (std::filesystem::is_directory(name_or_path, ec)) {
    throw InputError(detail::printable(name_or_path, 240) + ": is a directory, not a scene file");
  }
  return load_scene_file(name_or_path);
}

}  // namespace calder
