// SPDX-License-Identifier: MIT
#include "output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <system_error>
#include <utility>

#include <calder/error.hpp>

#include "errors.hpp"
#include "output_policy.hpp"
#include "progress.hpp"

namespace calder::app {

namespace {

// The temporary that exists now, for the signal handler (one at a time).
constexpr std::size_t kMaxPath = 4096;
char g_temp_path[kMaxPath] = {};
std::atomic<bool> g_has_temp{false};

extern "C" void remove_temp_and_reraise(int signal_number) {
  if (g_has_temp.load()) ::unlink(g_temp_path);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

// Every terminating signal that was not ignored at start removes the
// temporary and ends the process by that signal (the shell sees 128 + it).
void watch_signals(const std::string& temp) {
  if (temp.size() >= kMaxPath) return;
  std::memcpy(g_temp_path, temp.c_str(), temp.size() + 1);
  g_has_temp.store(true);
  for (const int signal_number : terminating_signals) {
    struct sigaction old {};
    ::sigaction(signal_number, nullptr, &old);
    if (old.sa_handler != SIG_IGN) std::signal(signal_number, remove_temp_and_reraise);
  }
}

void unwatch_signals() {
  g_has_temp.store(false);
  for (const int signal_number : terminating_signals) {
    struct sigaction old {};
    ::sigaction(signal_number, nullptr, &old);
    if (old.sa_handler == remove_temp_and_reraise) std::signal(signal_number, SIG_DFL);
  }
}

}  // namespace

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw InputError("output path is empty");
  if (is_stdout()) return;

  std::error_code ec;
  if (std::filesystem::is_directory(path_, ec)) {
    throw InputError(shown_path(path_) + ": is a directory, not a file");
  }
  const std::filesystem::path target(path_);
  const std::filesystem::path directory =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(directory, ec)) {
    throw InputError(shown_path(path_) + ": cannot create the file: directory '" +
                     shown_path(directory.string()) + "' does not exist");
  }
  {
    // A path that can't be created, or that the output policy refuses: bad
    // input (exit 2). Registered for the interrupt watchdog as it is made.
    const std::lock_guard<std::mutex> lock(temporaries_lock());
    file_.emplace("", path_);
    if (!file_->temp_path().empty()) {
      temporary_id_ = register_temporary(file_->temp_path(), false);
    }
  }
  if (!file_->temp_path().empty()) watch_signals(file_->temp_path());
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
  unwatch_signals();
  if (temporary_id_ != 0) unregister_temporary(std::exchange(temporary_id_, 0));
}

std::string OutputFile::write_error() const {
  if (is_stdout()) return "standard output: write failed";
  if (buffer_ && !buffer_->error().empty()) return buffer_->error();
  return "cannot write '" + detail::printable(path_, 240) + "'";
}

void OutputFile::check_stream(const std::ostream& s) {
  if (s) return;
  const std::string error = write_error();
  discard();
  throw RunError(error);
}

void OutputFile::discard() noexcept {
  if (!file_) return;
  file_->discard();
  file_.reset();
  unwatch_signals();
  if (temporary_id_ != 0) unregister_temporary(std::exchange(temporary_id_, 0));
}

OutputFile::Buffer::Buffer(calder::OutputFile& file) : file_(&file), data_(std::size_t{1} << 16) {
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
