// SPDX-License-Identifier: MIT
// calder's version, for the preprocessor and at run time. CMake checks that
// these numbers are project(VERSION) of CMakeLists.txt.
#pragma once

#include <string_view>

#define CALDER_VERSION_MAJOR 0
#define CALDER_VERSION_MINOR 1
#define CALDER_VERSION_PATCH 0
#define CALDER_VERSION_STRING "0.1.0"

namespace calder {

// The version of the calder library linked in, "MAJOR.MINOR.PATCH"; it can
// differ from CALDER_VERSION_STRING, the headers' version, when a program runs
// with another shared libcalder than the one it was compiled against.
[[nodiscard]] std::string_view version() noexcept;

}  // namespace calder
