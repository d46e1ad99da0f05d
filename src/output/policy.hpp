// SPDX-License-Identifier: MIT
// calder output module, inside: what the policy decides for one path
// (src/output/output.hpp), shared by the writers and check_outputs.
#pragma once

#include <sys/stat.h>

#include <string>

namespace calder::output::detail {

// "<who>: " or "".
std::string prefix(const std::string& who);

// What the kernel reached for a path about to be written.
struct Probe {
  enum class What {
    missing,  // nothing there yet (the folder exists)
    regular,  // a regular file we may replace or append to
    direct,   // a FIFO, a character device, a socket, a descriptor's path
    folder,   // a directory
  };
  What what = What::missing;
  std::string target;   // the path with links followed by the kernel
  struct stat info {};  // of what is there (regular, direct, folder)
  int fd = -1;          // direct: opened for writing (blocking), when `open_direct`
  bool waits = false;   // direct: a FIFO without a reader yet
};

// Applies the policy to `path`: throws InputError "<who>: refusing to write
// '<path>': <why>" (or "cannot write ...") when refused. Opens nothing for a
// regular or missing file; a direct one is opened when `open_direct` (and
// then waits for a FIFO's reader), else only looked at.
Probe probe(const std::string& who, const std::string& path, bool open_direct);

}  // namespace calder::output::detail
