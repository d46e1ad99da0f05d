// SPDX-License-Identifier: MIT
// calder command: an output file that appears whole or not at all.
//
// A buffered std::ostream onto output::AtomicFile (src/output/output.hpp), which
// decides how by the output policy (apps/README.md "Output files"): a new or
// regular file is written to a temporary in its folder, renamed over it only
// by commit(); a FIFO or a device is written directly; what the policy
// protects is refused (exit 2). Without commit() (an error, an exception) the
// temporary is removed; on a terminating signal the output module's handler
// removes it. The path "-" means standard output.
#pragma once

#include <memory>
#include <optional>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>
#include "../../src/output/output.hpp"

namespace calder::app {

// Throws when a write to standard output failed: Interrupted(SIGPIPE) when
// its reader went away (exit 141, no message), else RunError.
void check_standard_output(const std::ostream& out);

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

  // Throws RunError (after removing the temporary) if a write to `s` (this
  // file's stream, or standard output for "-") has failed: called after each
  // frame, it stops a run at its first failed write.
  void check_stream(const std::ostream& s);

 private:
  [[nodiscard]] std::string write_error() const;
  // A buffered stream onto calder::OutputFile::write_all; a failed write
  // sets badbit and keeps its error for commit().
  class Buffer : public std::streambuf {
   public:
    explicit Buffer(output::AtomicFile& file);
    bool flush_all();
    [[nodiscard]] const std::string& error() const { return error_; }

   protected:
    int_type overflow(int_type c) override;
    int sync() override;

   private:
    output::AtomicFile* file_;
    std::vector<char> data_;
    std::string error_;
  };

  void discard() noexcept;

  std::string path_;
  std::optional<output::AtomicFile> file_;
  std::unique_ptr<Buffer> buffer_;
  std::unique_ptr<std::ostream> out_;
  bool committed_ = false;
};

}  // namespace calder::app
