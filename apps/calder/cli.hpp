// SPDX-License-Identifier: MIT
// calder command: the verbs, parsed with CLI11, and the mapping of failures to
// exit codes (see errors.hpp).
#pragma once

#include <ostream>

namespace calder::app {

// Parses argv and runs the verb; returns the exit status. Output goes to
// `out`, the one-line error to `err`. Never throws.
int main(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace calder::app
