// SPDX-License-Identifier: MIT
// calder command: the scene named on the command line.
#pragma once

#include <string>

#include "calder/scene.hpp"

namespace calder::app {

// Whether `argument` is taken as a scene file rather than a built-in name:
// it names something that exists, ends in ".toml", or contains a '/'.
bool names_scene_file(const std::string& argument);

// The built-in scene of that name, or the scene file at that path.
// Throws InputError for an unknown name (listing the built-in scenes) or a
// directory, and calder::SceneFileError ("FILE:LINE:COLUMN: problem") for a
// scene file that can't be read or is invalid.
Scene load_scene_argument(const std::string& argument);

}  // namespace calder::app
