// SPDX-License-Identifier: MIT
// calder command: the scene named on the command line.
#pragma once

#include <string>

#include "calder/scene.hpp"

namespace calder::app {

// The built-in scene of that name, or the scene file at that path
// (calder::load_scene: the rule Python follows too). Throws InputError for an
// unknown name (listing the built-in scenes) or a directory, and
// calder::SceneFileError ("FILE:LINE:COLUMN: problem") for a scene file that
// can't be read or is invalid.
Scene load_scene_argument(const std::string& argument);

}  // namespace calder::app
