// SPDX-License-Identifier: MIT
#include "calder/output_file.hpp"

#include <fcntl.h>
#include <limits.h>
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

std::string directory_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

// The temporary file's name: ".<name>.tmp-XXXXXX" in the folder of `path`,
// or ".calder.tmp-XXXXXX" where that would pass the file-name limit.
std::string temp_template(const std::string& path) {
  const std::string dir = directory_of(path);
  const std::string name = path.substr(dir.size());
  constexpr std::size_t kNameMax = 255;  // NAME_MAX of Linux file systems
  const std::string temp = "." + name + ".tmp-XXXXXX";
  return dir + (temp.size() <= kNameMax ? temp : std::string(".calder.tmp-XXXXXX"));
}

// The path a symbolic link chain ends at (the path itself if not a link);
// errno ELOOP after 40 links, as the kernel counts.
std::string follow_links(std::string path, int& error) {
  for (int hops = 0; hops < 40; ++hops) {
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0 || !S_ISLNK(info.st_mode)) return path;
    std::vector<char> target(PATH_MAX + 1);
    const ssize_t n = ::readlink(path.c_str(), target.data(), target.size() - 1);
    if (n < 0) {
      error = errno;
      return path;
    }
    const std::string link(target.data(), static_cast<std::size_t>(n));
    path = link.front() == '/' ? link : directory_of(path) + link;
  }
  error = ELOOP;
  return path;
}

bool is_under(const std::string& path, const char* prefix) { return path.rfind(prefix, 0) == 0; }

}  // namespace

OutputFile::OutputFile(std::string who, std::string path)
    : who_(std::move(who)), path_(std::move(path)) {
  if (path_.empty() || path_.back() == '/') {
    throw Error(prefix() + "not a file name: '" + detail::printable(path_, 240) + "'");
  }
  int error = 0;
  target_ = follow_links(path_, error);
  if (error != 0) fail("follow the link", error);

  struct stat info {};
  const bool exists = ::stat(target_.c_str(), &info) == 0;
  if (exists && S_ISDIR(info.st_mode)) fail("write", EISDIR);
  if (exists && S_ISBLK(info.st_mode)) {
    throw Error(prefix() + "refusing to write to the block device '" +
                detail::printable(path_, 240) + "'");
  }
  // A FIFO, a character device (/dev/null, /dev/tty), /dev/stdout or
  // /proc/self/fd/N: written directly, in order; never replaced.
  const bool through_dev = is_under(path_, "/dev/") || is_under(path_, "/proc/");
  if ((exists && !S_ISREG(info.st_mode)) || (exists && through_dev)) {
    direct_ = true;
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC | (S_ISREG(info.st_mode) ? O_APPEND : 0));
    if (fd_ < 0) fail("open", errno);
    return;
  }

  std::string name = temp_template(target_);
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  fd_ = ::mkstemp(buffer.data());
  if (fd_ < 0) fail("create a file for", errno);
  temp_path_ = buffer.data();
  // mkstemp creates 0600: an existing file keeps its mode (and owner, where
  // allowed), a new one gets 0644 whatever the umask (as calder always did).
  const mode_t mode = exists ? (info.st_mode & 07777) : mode_t{0644};
  if (exists) (void)!::fchown(fd_, info.st_uid, info.st_gid);
  if (::fchmod(fd_, mode) != 0) {
    error = errno;
    discard();
    fail("set the mode of", error);
  }
}

OutputFile::~OutputFile() { discard(); }

std::string OutputFile::prefix() const { return who_.empty() ? std::string() : who_ + ": "; }

void OutputFile::fail(const char* what, int error) const {
  throw Error(prefix() + "cannot " + what + " '" + detail::printable(path_, 240) +
              "': " + std::generic_category().message(error));
}

void OutputFile::write_all(const void* data, std::size_t size) {
  if (fd_ < 0) fail("write", error_ != 0 ? error_ : EBADF);
  const auto* bytes = static_cast<const unsigned char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd_, bytes, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      error_ = errno;
      discard();
      fail("write", error_);
    }
    bytes += n;
    size -= static_cast<std::size_t>(n);
  }
}

void OutputFile::commit() {
  if (done_) throw Error(prefix() + "'" + path_ + "' was already written or abandoned");
  if (!direct_ && ::fsync(fd_) != 0) {
    const int error = errno;
    discard();
    fail("write", error);
  }
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0 && errno != EINTR) {
    const int error = errno;
    discard();
    fail("write", error);
  }
  if (!direct_ && std::rename(temp_path_.c_str(), target_.c_str()) != 0) {
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
