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

bool all_digits(const std::string& text) {
  if (text.empty()) return false;
  for (const char c : text) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// Whether `path` names a descriptor the process already has open
// (/dev/stdout, /dev/fd/3, /proc/self/fd/3): written through, as "-" is.
bool names_a_descriptor(const std::string& path) {
  if (path == "/dev/stdout" || path == "/dev/stderr") return true;
  if (path.rfind("/dev/fd/", 0) == 0) return all_digits(path.substr(8));
  if (path.rfind("/proc/", 0) != 0) return false;
  const std::size_t fd = path.find("/fd/", 6);
  if (fd == std::string::npos) return false;
  const std::string process = path.substr(6, fd - 6);
  return (process == "self" || process == "thread-self" || all_digits(process)) &&
         all_digits(path.substr(fd + 4));
}

// The folder's status of the folder holding `path` (".": none in the path).
bool folder_status(const std::string& path, struct stat& info) {
  const std::string dir = directory_of(path);
  return ::stat(dir.empty() ? "." : dir.c_str(), &info) == 0;
}

}  // namespace

std::string foreign_owner_refusal(const std::string& path) {
  struct stat info {};
  struct stat folder {};
  if (::lstat(path.c_str(), &info) != 0 || !folder_status(path, folder)) return std::string();
  if ((folder.st_mode & S_ISVTX) == 0) return std::string();
  if (info.st_uid == ::geteuid() || info.st_uid == folder.st_uid) return std::string();
  const char* what = S_ISLNK(info.st_mode)   ? "the symbolic link"
                     : S_ISDIR(info.st_mode) ? "the folder"
                                             : "the file";
  return std::string(what) + " is another user's, in a shared (sticky) folder";
}

std::string opened_path(int fd) {
  std::vector<char> buffer(PATH_MAX + 1);
  const std::string link = "/proc/self/fd/" + std::to_string(fd);
  const ssize_t n = ::readlink(link.c_str(), buffer.data(), buffer.size() - 1);
  if (n <= 0 || buffer[0] != '/') return std::string();
  return std::string(buffer.data(), static_cast<std::size_t>(n));
}

// The output policy (calder/output_file.hpp; apps/README.md, "Output files").
// Nothing is resolved by hand: the path is opened by the kernel, which
// follows links with its own checks, and what it opened decides the rest.
OutputFile::OutputFile(std::string who, std::string path)
    : who_(std::move(who)), path_(std::move(path)) {
  if (path_.empty() || path_.back() == '/') {
    throw Error(prefix() + "not a file name: '" + detail::printable(path_, 240) + "'");
  }
  struct stat link {};
  const bool is_link = ::lstat(path_.c_str(), &link) == 0 && S_ISLNK(link.st_mode);
  if (is_link) {
    const std::string why = foreign_owner_refusal(path_);
    if (!why.empty()) refuse(why.c_str());
  }
  // Opened for writing, never created and never truncated: the kernel says
  // whether we may write it (permissions, fs.protected_symlinks) and what it is.
  const int probe = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (probe < 0) {
    const int error = errno;
    if (error == ENXIO) {  // a FIFO without a reader yet: wait for one
      open_direct(::open(path_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC));
      return;
    }
    struct stat info {};
    if ((error == EACCES || error == EPERM) && ::stat(path_.c_str(), &info) == 0 &&
        S_ISREG(info.st_mode)) {
      refuse("it is write-protected (the system refuses us write access, as the shell's > would)");
    }
    if (error != ENOENT) fail("write", error);
    if (is_link) refuse("it is a symbolic link to a missing file");
    target_ = path_;
    create_temporary(nullptr);
    return;
  }
  struct stat info {};
  if (::fstat(probe, &info) != 0) {
    const int error = errno;
    ::close(probe);
    fail("write", error);
  }
  if (!S_ISREG(info.st_mode) || names_a_descriptor(path_)) {
    if (S_ISBLK(info.st_mode)) {
      ::close(probe);
      throw Error(prefix() + "refusing to write to the block device '" +
                  detail::printable(path_, 240) + "'");
    }
    // A FIFO, a character device (/dev/null, a terminal), a socket, or a
    // descriptor's file (/dev/stdout): written directly, in order.
    const int flags = ::fcntl(probe, F_GETFL);
    (void)::fcntl(probe, F_SETFL, (flags & ~O_NONBLOCK) | (S_ISREG(info.st_mode) ? O_APPEND : 0));
    open_direct(probe);
    return;
  }
  target_ = is_link ? opened_path(probe) : path_;
  ::close(probe);
  if (target_.empty()) refuse("the link can't be followed safely without /proc");
  if ((info.st_mode & 0222) == 0) refuse("it is write-protected (no write permission for anyone)");
  const std::string why = foreign_owner_refusal(target_);
  if (!why.empty()) refuse(why.c_str());
  create_temporary(&info);
}

void OutputFile::refuse(const char* why) const {
  throw Error(prefix() + "refusing to write '" + detail::printable(path_, 240) + "': " + why);
}

void OutputFile::open_direct(int fd) {
  if (fd < 0) fail("open", errno);
  direct_ = true;
  fd_ = fd;
}

// A temporary beside target_: mkstemp creates it (O_EXCL: never through a
// link) 0600; an existing file's mode (and owner, where allowed) is kept, a
// new one gets 0644 whatever the umask.
void OutputFile::create_temporary(const struct stat* existing) {
  const std::string name = temp_template(target_);
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  fd_ = ::mkstemp(buffer.data());
  if (fd_ < 0) fail("create a file for", errno);
  temp_path_ = buffer.data();
  const mode_t mode = existing != nullptr ? (existing->st_mode & 07777) : mode_t{0644};
  if (existing != nullptr) (void)!::fchown(fd_, existing->st_uid, existing->st_gid);
  if (::fchmod(fd_, mode) != 0) {
    const int error = errno;
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
