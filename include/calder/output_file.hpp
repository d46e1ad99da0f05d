// SPDX-License-Identifier: MIT
// calder: output files that appear whole or not at all (part of
// calder::render; the `calder` command's trajectories use it too).
//
// The output policy (apps/README.md, "Output files"). The path is opened by
// the kernel (never created, never truncated), which follows links with its
// own checks (permissions, fs.protected_symlinks); what it opened decides:
//   - nothing yet: the data goes to a temporary file (".<name>.tmp-XXXXXX")
//     in the same folder, which commit() flushes to disk and renames over the
//     path; a new file gets 0644, whatever the umask. Destroyed without
//     commit(), it removes the temporary: the path is untouched.
//   - a regular file: replaced in the same way (never appended to), keeping
//     its mode (and owner, where allowed); through a symbolic link, the file
//     the kernel reached is replaced and the link stays. Refused: a file we
//     may not write, a file without any write permission (0444, even for
//     root), a file or a link that another user owns in a sticky folder (/tmp)
//     unless the folder is theirs, a link to nothing.
//   - a FIFO, a character device (/dev/null, /dev/full, a terminal), a socket,
//     or a path naming an open descriptor (/dev/stdout, /dev/fd/N,
//     /proc/self/fd/N): written directly, in order, never replaced.
//   - a directory or a block device: refused.
// Errors throw calder::Error naming the path, the operation and the
// system's reason, e.g. "cannot write 'out.csv': No space left on device";
// the first failed write removes the temporary at once.
#pragma once

#include <cstddef>
#include <string>

struct stat;

namespace calder {

// Why the output policy refuses what `path` names ("" when it doesn't): a
// symbolic link, file or folder that another user than us and the folder's
// owner owns in a sticky folder (/tmp): the cases of the kernel's
// fs.protected_symlinks and fs.protected_regular, whatever their settings.
std::string foreign_owner_refusal(const std::string& path);

// The path the kernel reached when it opened `fd` (links followed with its
// own checks), from /proc/self/fd; "" where /proc is not mounted.
std::string opened_path(int fd);

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
  [[noreturn]] void refuse(const char* why) const;
  void open_direct(int fd);
  void create_temporary(const struct stat* existing);

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
