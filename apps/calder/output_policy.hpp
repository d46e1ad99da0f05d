// SPDX-License-Identifier: MIT
// calder command: the output policy is calder's output module
// (src/output/output.hpp); the names the verbs use, here.
#pragma once

#include "../../src/output/output.hpp"

namespace calder::app {

using output::check_outputs;
using output::NamedPath;
using output::quoted_path;
using output::shown_path;

}  // namespace calder::app
