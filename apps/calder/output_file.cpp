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
#include <system_error>
#include <utility>

#include "errors.hpp"

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

void watch_signals(const std::string& temp) {
  if (temp.size() >= kMaxPath) return;
  std::memcpy(g_temp_path, temp.c_str(), temp.size() + 1);
  g_has_temp.store(true);
  std::signal(SIGINT, remove_temp_and_reraise);
  std::signal(SIGTERM, remove_temp_and_reraise);
}

void unwatch_signals() {
  g_has_temp.store(false);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

std::string error_text(int error) { return std::strerror(error); }

}  // namespace

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw InputError("output path is empty");
  if (is_stdout()) return;

  std::error_code ec;
  if (std::filesystem::is_directory(path_, ec)) {
    throw InputError(path_ + ": is a directory, not a file");
  }
  const std::filesystem::path target(path_);
  const std::filesystem::path directory =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(directory, ec)) {
    throw InputError(path_ + ": cannot create the file: directory '" + directory.string() +
                     "' does not exist");
  }
  // (Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "." + name + ...)
  std::string temp_name = ".";
  temp_name += target.filename().string();
  temp_name += ".tmp-XXXXXX";
  std::string pattern = (directory / temp_name).string();
  const int fd = ::mkstemp(pattern.data());
  if (fd < 0) {
    const int error = errno;
    throw InputError(path_ + ": cannot create the file: " + error_text(error));
  }
  temp_path_ = pattern;
  watch_signals(temp_path_);
  // mkstemp makes the file private (0600); give it the mode a new file gets.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  const mode_t mode = static_cast<mode_t>(0666) & ~mask;
  (void)::fchmod(fd, mode);
  ::close(fd);

  buffer_.resize(std::size_t{1} << 16);
  file_.rdbuf()->pubsetbuf(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  file_.open(temp_path_, std::ios::binary | std::ios::trunc);
  if (!file_) {
    const int error = errno;
    discard();
    throw InputError(path_ + ": cannot create the file: " + error_text(error));
  }
}

OutputFile::~OutputFile() {
  if (!committed_) discard();
}

std::ostream& OutputFile::stream() {
  if (is_stdout()) return std::cout;
  return file_;
}

void OutputFile::commit() {
  if (is_stdout()) {  // the caller flushes and checks its stream
    committed_ = true;
    return;
  }
  file_.flush();
  const bool written = static_cast<bool>(file_);
  const int write_error = errno;
  file_.close();
  if (!written || !file_) {
    discard();
    throw RunError(path_ + ": write failed: " + error_text(write_error));
  }
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    discard();
    throw RunError(path_ + ": cannot replace the file: " + error_text(error));
  }
  committed_ = true;
  unwatch_signals();
}

void OutputFile::discard() noexcept {
  if (temp_path_.empty()) return;
  if (file_.is_open()) file_.close();
  ::unlink(temp_path_.c_str());
  temp_path_.clear();
  unwatch_signals();
}

}  // namespace calder::app
