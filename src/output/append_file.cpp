// SPDX-License-Identifier: MIT
// calder output module: a regular file appended to under an exclusive lock,
// put back as it was unless kept (output.hpp, AppendFile).
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>
#include <utility>

#include "calder/error.hpp"
#include "output.hpp"
#include "policy.hpp"

namespace calder::output {

namespace {

std::string system_message(int error) { return std::generic_category().message(error); }

// Writes all of `bytes` at `offset`; false (errno set) on failure.
bool write_at(int fd, std::span<const std::uint8_t> bytes, std::uint64_t offset) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n =
        ::pwrite(fd, bytes.data() + done, bytes.size() - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

AppendFile::AppendFile(std::string who, std::string path)
    : who_(std::move(who)), path_(std::move(path)) {
  const detail::Probe p = detail::probe(who_, path_, false);
  const std::string named = detail::prefix(who_) + quoted_path(path_);
  if (p.what == detail::Probe::What::folder) {
    throw InputError(named + " is a directory, not a file");
  }
  if (p.what == detail::Probe::What::direct) {
    throw InputError(detail::prefix(who_) + "refusing to write " + quoted_path(path_) +
                     ": it must be a regular file (it is read back, then appended to)");
  }
  target_ = p.target;
  if (p.what == detail::Probe::What::missing) {
    // Never through a link planted meanwhile, never over a file made meanwhile.
    fd_ = ::open(target_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd_ < 0) {
      throw InputError(named + ": cannot create it: " + system_message(errno));
    }
    created_ = true;
    (void)::fchmod(fd_, 0644);
  } else {
    fd_ = ::open(target_.c_str(), O_RDWR | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC);
    struct stat now {};
    if (fd_ < 0 || ::fstat(fd_, &now) != 0) {
      const int error = errno;
      if (fd_ >= 0) ::close(std::exchange(fd_, -1));
      throw InputError(named + ": cannot open it: " + system_message(error));
    }
    if (!S_ISREG(now.st_mode) || now.st_dev != p.info.st_dev || now.st_ino != p.info.st_ino) {
      ::close(std::exchange(fd_, -1));
      throw InputError(named + ": it was replaced while it was opened; try again");
    }
    original_size_ = static_cast<std::uint64_t>(now.st_size);
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    if (created_) ::unlink(target_.c_str());
    ::close(std::exchange(fd_, -1));
    if (error == EWOULDBLOCK) {
      throw InputError(named +
                       ": another process is writing it (it is locked); wait for it to "
                       "finish or give another file");
    }
    throw InputError(named + ": cannot lock it: " + system_message(error));
  }
  cut_ = end_ = original_size_;
}

AppendFile::~AppendFile() {
  if (!kept_) rollback();
  if (fd_ >= 0) ::close(fd_);  // and the lock goes with it
}

void AppendFile::fail(const char* what, int error) const {
  throw RunError(detail::prefix(who_) + "cannot " + what + " " + quoted_path(path_) + ": " +
                 system_message(error));
}

std::vector<std::uint8_t> AppendFile::read_at(std::uint64_t offset, std::size_t size) const {
  std::vector<std::uint8_t> bytes(size);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n =
        ::pread(fd_, bytes.data() + done, size - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("read", errno);
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  bytes.resize(done);
  return bytes;
}

void AppendFile::cut_to(std::uint64_t length) {
  if (touched_ || length > original_size_) {
    throw RunError(detail::prefix(who_) + quoted_path(path_) +
                   ": can only be cut once, before anything is appended, within its length");
  }
  tail_ = read_at(length, static_cast<std::size_t>(original_size_ - length));
  touched_ = true;
  if (::ftruncate(fd_, static_cast<off_t>(length)) != 0) fail("write", errno);
  cut_ = end_ = length;
}

void AppendFile::append(std::span<const std::uint8_t> bytes) {
  touched_ = true;
  if (!write_at(fd_, bytes, end_)) fail("write", errno);
  end_ += bytes.size();
}

void AppendFile::sync() {
  if (::fsync(fd_) != 0) fail("write", errno);
}

void AppendFile::rollback() noexcept {
  if (fd_ < 0) return;
  if (created_) {
    ::unlink(target_.c_str());
    created_ = false;
    return;
  }
  if (!touched_) return;
  // Back to the original length first, then the bytes that followed the cut.
  (void)::ftruncate(fd_, static_cast<off_t>(cut_));
  (void)write_at(fd_, tail_, cut_);
  (void)::fsync(fd_);
  end_ = original_size_;
  touched_ = false;
}

}  // namespace calder::output
