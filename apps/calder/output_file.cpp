// SPDX-License-Identifier: MIT
#include "output_file.hpp"

#include <cerrno>
#include <csignal>
#include <iostream>
#include <utility>

#include <calder/error.hpp>

#include "errors.hpp"
#include "output_policy.hpp"
#include "progress.hpp"

namespace calder::app {

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw InputError("output path is empty");
  if (is_stdout()) return;

  // A path that can't be created, or that the output policy refuses: bad
  // input (exit 2). The temporary is registered for the signal handler.
  file_.emplace("", path_);
  buffer_ = std::make_unique<Buffer>(*file_);
  out_ = std::make_unique<std::ostream>(buffer_.get());
}

OutputFile::~OutputFile() {
  if (!committed_) discard();
}

std::ostream& OutputFile::stream() {
  if (is_stdout()) return std::cout;
  return *out_;
}

void OutputFile::commit() {
  if (is_stdout()) {  // the caller flushes and checks its stream
    committed_ = true;
    return;
  }
  if (!buffer_->flush_all() || !*out_) {
    const std::string error = write_error();
    discard();
    throw RunError(error);
  }
  try {
    file_->commit();
  } catch (const calder::Error& e) {
    discard();
    throw RunError(e.what());
  }
  committed_ = true;
}

std::string OutputFile::write_error() const {
  if (is_stdout()) return "standard output: write failed";
  if (buffer_ && !buffer_->error().empty()) return buffer_->error();
  return "cannot write '" + detail::printable(path_, 240) + "'";
}

void check_standard_output(const std::ostream& out) {
  if (out) return;
  // The reader went away (`calder run ... | head`): the run ends as if by
  // SIGPIPE, quietly, whether the signal was caught or ignored.
  if (errno == EPIPE || output::InterruptScope::signal() == SIGPIPE) throw Interrupted(SIGPIPE);
  throw RunError("standard output: write failed");
}

void OutputFile::check_stream(const std::ostream& s) {
  if (s) return;
  if (is_stdout()) check_standard_output(s);
  const std::string error = write_error();
  discard();
  throw RunError(error);
}

void OutputFile::discard() noexcept {
  if (!file_) return;
  file_->discard();
  file_.reset();
}

OutputFile::Buffer::Buffer(output::AtomicFile& file) : file_(&file), data_(std::size_t{1} << 16) {
  setp(data_.data(), data_.data() + data_.size());
}

bool OutputFile::Buffer::flush_all() {
  if (!error_.empty()) return false;  // the first failure stands; the file is gone
  const auto size = static_cast<std::size_t>(pptr() - pbase());
  if (size == 0) return error_.empty();
  try {
    file_->write_all(pbase(), size);
  } catch (const calder::Error& e) {
    error_ = e.what();
    return false;
  }
  setp(data_.data(), data_.data() + data_.size());
  return true;
}

OutputFile::Buffer::int_type OutputFile::Buffer::overflow(int_type c) {
  if (!flush_all()) return traits_type::eof();
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
  }
  return traits_type::not_eof(c);
}

int OutputFile::Buffer::sync() { return flush_all() ? 0 : -1; }

}  // namespace calder::app
