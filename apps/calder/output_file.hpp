// SPDX-License-Identifier: MIT
// calder command: an output file that appears whole or not at all.
//
// calder::OutputFile decides how, by the output policy (calder/output_file.hpp,
// apps/README.md "Output files"): a new or regular file is written to a
// temporary in its folder, renamed over it only by commit(), after everything
// was written and flushed; a link is followed by the kernel; a FIFO or a
// device is written directly; what the policy protects is refused (exit 2).
// If commit() is never reached (an error, an exception) the destructor
// removes the temporary; so does every terminating signal while one exists
// (progress.hpp, and its watchdog). The target is never left half written.
// The path "-" means standard output.
#pragma once

#include <calder/output_file.hpp>
#include <memory>
#include <optional>
#include <ostream>
#include <streambuf>
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
    explicit Buffer(calder::OutputFile& file);
    bool flush_all();
    [[nodiscard]] const std::string& error() const { return error_; }

   protected:
    int_type overflow(int_type c) override;
    int sync() override;

   private:
    calder::OutputFile* file_;
    std::vector<char> data_;
    std::string error_;
  };

  void discard() noexcept;

  std::string path_;
  std::optional<calder::OutputFile> file_;  // the atomic file itself (calder::render)
  std::unique_ptr<Buffer> buffer_;
  std::unique_ptr<std::ostream> out_;
  std::size_t temporary_id_ = 0;  // registered with the interrupt watchdog
  bool committed_ = false;
};

}  // namespace calder::app
