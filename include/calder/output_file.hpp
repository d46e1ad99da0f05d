// SPDX-License-Identifier: MIT
// calder: output files that appear whole or not at all (part of
// calder::render; the `calder` command's trajectories use it too).
//
// What happens depends on what the path names (docs/SCENES.md, "Output files"):
//   - a regular file, or nothing yet: the data goes to a temporary file
//     (".<name>.tmp-XXXXXX") in the same folder, which commit() flushes to
//     disk and renames over the path. An existing file keeps its mode (and
//     owner where allowed); a new one gets 0644, whatever the umask. Destroyed
//     without commit(), it removes the temporary: the path is untouched.
//   - a symbolic link: followed; its final target is written as above (the
//     link stays a link).
//   - a FIFO, a character device (/dev/null, /dev/full, a terminal) or a
//     path under /dev/ or /proc/ (/dev/stdout): opened and written directly,
//     in order, never replaced.
//   - a directory or a block device: refused.
// Errors throw calder::Error naming the path, the operation and the
// system's reason, e.g. "cannot write 'out.csv': No space left on device";
// the first failed write removes the temporary at once.
#pragma once

#include <cstddef>
#include <string>

namespace calder {

class OutputFile {
 public:
  // `who` prefixes error messages ("Canvas::write_png"; empty: no prefix).
  OutputFile(std::string who, std::string path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // The open descriptor of the temporary file (-1 once committed or
  // discarded). Whoever needs their own (giflib closes the one it is given)
  // dup()s it.
  [[nodiscard]] int fd() const { return fd_; }
  // Writes all bytes; throws on failure.
  void write_all(const void* data, std::size_t size);

  void commit();
  // Removes the temporary file now (idempotent, never throws).
  void discard() noexcept;

  [[nodiscard]] const std::string& path() const { return path_; }
  // The temporary file ("" when written directly).
  [[nodiscard]] const std::string& temp_path() const { return temp_path_; }
  // Whether the path is written directly (a FIFO, a device, /dev/stdout).
  [[nodiscard]] bool direct() const { return direct_; }
  // Throws calder::Error("<who>: cannot <what> '<path>': <strerror(error)>").
  [[noreturn]] void fail(const char* what, int error) const;

 private:
  [[nodiscard]] std::string prefix() const;

  std::string who_;
  std::string path_;
  std::string target_;  // path_ with symbolic links followed
  std::string temp_path_;
  int fd_ = -1;
  int error_ = 0;  // of the first failed write
  bool direct_ = false;
  bool done_ = false;  // committed or discarded
};

}  // namespace calder
