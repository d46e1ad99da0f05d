// SPDX-License-Identifier: MIT
// calder: files written atomically with mode 0644 (part of calder::render;
// the `calder` command's trajectories use it too).
//
// An OutputFile is a temporary file in the folder of its final path, opened
// for writing; commit() gives it mode 0644 (whatever the umask), flushes it
// to disk and renames it over the final path. Destroyed without commit(),
// it removes the temporary file. Errors throw calder::Error naming the final
// path and the operation that failed.
#pragma once

#include <cstddef>
#include <string>

namespace calder {

class OutputFile {
 public:
  // `who` prefixes error messages ("Canvas::write_png").
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
  [[nodiscard]] const std::string& temp_path() const { return temp_path_; }
  // Throws calder::Error("<who>: cannot <what> '<path>': <strerror(error)>").
  [[noreturn]] void fail(const char* what, int error) const;

 private:
  std::string who_;
  std::string path_;
  std::string temp_path_;
  int fd_ = -1;
  bool done_ = false;  // committed or discarded
};

}  // namespace calder
