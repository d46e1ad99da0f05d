// SPDX-License-Identifier: MIT
// calder: scene files (TOML), read into a Scene and written back.
//
// The format is documented in docs/SCENES.md. Errors are one line naming the
// file, the line and column, and the problem, e.g.
//   scenes/rain.toml:12:3: unknown key 'mas' in [[bodies]] (did you mean 'mass'?)
// This part of calder needs toml++ (target calder::scene_file); the core
// library stays free of dependencies.
#pragma once

#include <string>
#include <string_view>

#include "calder/error.hpp"
#include "calder/scene.hpp"

namespace calder {

// A scene file that can't be read or doesn't describe a valid scene.
// what() is one line: "FILE:LINE:COLUMN: problem" (or "FILE: problem").
class SceneFileError : public InputError {
 public:
  using InputError::InputError;
};

// Reads and validates a scene file.
Scene load_scene_file(const std::string& path);

// A scene argument as the front ends take it (the calder command, Python): a
// scene file's path when it names one (names_scene_file: a path that exists,
// ends in .toml or holds a '/'), else a built-in scene's name. Throws
// calder::InputError for an empty name, a folder, or a word that is neither
// (unknown_scene_message, the current folder's .toml files among the
// candidates it suggests).
Scene load_scene(const std::string& name_or_path);
bool names_scene_file(const std::string& argument);

// Parses scene text; source_name stands for the file in error messages.
Scene parse_scene(std::string_view text, const std::string& source_name);

// Writes a scene as TOML that parse_scene reads back to an equal scene
// (custom callables, which data can't hold, are refused with an Error).
std::string to_toml(const Scene& scene);

}  // namespace calder
