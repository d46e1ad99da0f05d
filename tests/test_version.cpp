// SPDX-License-Identifier: MIT
// calder::version() is the library's version; the macros are the headers' own.
// CMake checks the header against project(VERSION) when it configures.
#include <gtest/gtest.h>

#include <string>

#include "calder/version.hpp"

TEST(Version, LibraryVersionIsTheHeadersVersion) {
  EXPECT_EQ(calder::version(), CALDER_VERSION_STRING);
}

TEST(Version, StringSpellsTheNumbers) {
  const std::string spelled = std::to_string(CALDER_VERSION_MAJOR) + "." +
                              std::to_string(CALDER_VERSION_MINOR) + "." +
                              std::to_string(CALDER_VERSION_PATCH);
  EXPECT_EQ(spelled, CALDER_VERSION_STRING);
}
