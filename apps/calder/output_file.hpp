// calder command: an output file that appears whole or not at all.
//
// The data goes to a temporary file in the target's directory (a hidden
// ".NAME.tmp-XXXXXX"), which is renamed over the target only by commit(),
// after everything was written and flushed. If commit() is never reached (an
// error, an exception) the destructor removes the temporary; so does SIGINT
// or SIGTERM while one exists. The target is never left half written.
// The path "-" means standard output (written directly, nothing to rename).
#pragma once

#include <fstream>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace calder::app {

class OutputFile {
 public:
  // Creates the temporary file. Throws InputError naming `path` when it can't
  // be created (a missing directory, no permission, the path is a directory).
  explicit OutputFile(std::string path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // The temporary file's stream (std::cout for "-").
  std::ostream& stream();
  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] bool is_stdout() const { return path_ == "-"; }

  // Flushes, closes and renames the temporary over the target. Throws
  // RunError (after removing the temporary) if any write failed. For "-"
  // it does nothing: the caller flushes and checks standard output.
  void commit();

 private:
  void discard() noexcept;

  std::string path_;
  std::string temp_path_;
  std::vector<char> buffer_;
  std::ofstream file_;
  bool committed_ = false;
};

}  // namespace calder::app
