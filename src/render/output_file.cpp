// SPDX-License-Identifier: MIT
#include "calder/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <system_error>
#include <utility>
#include <vector>

#include "calder/error.hpp"

namespace calder {

namespace {

// The temporary file's name: ".<name>.XXXXXX" in the folder of `path`.
std::string temp_template(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  return dir + "." + name + ".XXXXXX";
}

}  // namespace

OutputFile::OutputFile(std::string who, std::string path)
    : who_(std::move(who)), path_(std::move(path)) {
  if (path_.empty() || path_.back() == '/') {
    throw Error(who_ + ": not a file name: '" + path_ + "'");
  }
  std::string name = temp_template(path_);
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  fd_ = ::mkstemp(buffer.data());
  if (fd_ < 0) fail("create a file for", errno);
  temp_path_ = buffer.data();
  // mkstemp creates 0600; the final file is 0644 whatever the umask.
  if (::fchmod(fd_, 0644) != 0) {
    const int error = errno;
    discard();
    fail("set the mode of", error);
  }
}

OutputFile::~OutputFile() { discard(); }

void OutputFile::fail(const char* what, int error) const {
  throw Error(who_ + ": cannot " + what + " '" + path_ +
              "': " + std::generic_category().message(error));
}

void OutputFile::write_all(const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd_, bytes, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int error = errno;
      discard();
      fail("write", error);
    }
    bytes += n;
    size -= static_cast<std::size_t>(n);
  }
}

void OutputFile::commit() {
  if (done_) throw Error(who_ + ": '" + path_ + "' was already written or abandoned");
  if (::fsync(fd_) != 0) {
    const int error = errno;
    discard();
    fail("write", error);
  }
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0) {
    const int error = errno;
    discard();
    fail("write", error);
  }
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    discard();
    fail("rename a temporary file to", error);
  }
  done_ = true;
}

void OutputFile::discard() noexcept {
  if (done_) return;
  done_ = true;
  if (fd_ >= 0) ::close(std::exchange(fd_, -1));
  if (!temp_path_.empty()) ::unlink(temp_path_.c_str());
}

}  // namespace calder
