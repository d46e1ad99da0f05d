// SPDX-License-Identifier: MIT
#include "calder/version.hpp"

namespace calder {

std::string_view version() noexcept { return CALDER_VERSION_STRING; }

}  // namespace calder
