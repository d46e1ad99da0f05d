// SPDX-License-Identifier: MIT
// calder output module: a file that appears whole or not at all
// (output.hpp, AtomicFile).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <system_error>
#include <utility>
#include <vector>

#include "calder/error.hpp"
#include "output.hpp"
#include "policy.hpp"

namespace calder::output {

namespace {

std::string directory_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

// The temporary's name: ".<name>.tmp-XXXXXX" in the folder of `path`, or
// ".calder.tmp-XXXXXX" where that would pass the file-name limit.
std::string temp_template(const std::string& path) {
  const std::string dir = directory_of(path);
  const std::string name = path.substr(dir.size());
  constexpr std::size_t kNameMax = 255;  // NAME_MAX of Linux file systems
  const std::string temp = "." + name + ".tmp-XXXXXX";
  return dir + (temp.size() <= kNameMax ? temp : std::string(".calder.tmp-XXXXXX"));
}

}  // namespace

AtomicFile::AtomicFile(std::string who, std::string path)
    : who_(std::move(who)), path_(std::move(path)) {
  detail::Probe p = detail::probe(who_, path_, true);
  if (p.what == detail::Probe::What::folder) {
    throw InputError(detail::prefix(who_) + shown_path(path_) + ": is a directory, not a file");
  }
  if (p.what == detail::Probe::What::direct) {
    direct_ = true;
    fd_ = p.fd;
    return;
  }
  target_ = p.target;
  const bool existed = p.what == detail::Probe::What::regular;
  // mkostemp creates it with O_CREAT | O_EXCL (never through a link), 0600;
  // registered under the registry's lock so that the watchdog never misses it.
  std::vector<char> name;
  {
    const std::string pattern = temp_template(target_);
    name.assign(pattern.begin(), pattern.end());
    name.push_back('\0');
    const std::lock_guard<std::mutex> lock(temporaries_lock());
    fd_ = ::mkostemp(name.data(), O_CLOEXEC);
    if (fd_ < 0) {
      const int error = errno;
      throw InputError(detail::prefix(who_) + "cannot create a file for " + quoted_path(path_) +
                       ": " + std::generic_category().message(error));
    }
    temp_path_ = name.data();
    temporary_id_ = register_temporary(temp_path_, false);
  }
  // An existing file's mode (and owner, where allowed) is kept; a new one
  // gets 0644 whatever the umask.
  const mode_t mode = existed ? (p.info.st_mode & 07777) : mode_t{0644};
  if (existed) (void)!::fchown(fd_, p.info.st_uid, p.info.st_gid);
  if (::fchmod(fd_, mode) != 0) {
    const int error = errno;
    discard();
    throw InputError(detail::prefix(who_) + "cannot set the mode of " + quoted_path(path_) + ": " +
                     std::generic_category().message(error));
  }
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::fail(const char* what, int error) const {
  throw RunError(detail::prefix(who_) + "cannot " + what + " " + quoted_path(path_) + ": " +
                 std::generic_category().message(error));
}

void AtomicFile::write_all(const void* data, std::size_t size) {
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

void AtomicFile::commit() {
  if (done_) {
    throw RunError(detail::prefix(who_) + quoted_path(path_) + " was already written or abandoned");
  }
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
  if (!direct_) {
    const std::lock_guard<std::mutex> lock(temporaries_lock());
    if (std::rename(temp_path_.c_str(), target_.c_str()) != 0) {
      const int error = errno;
      ::unlink(temp_path_.c_str());
      unregister_temporary_locked(std::exchange(temporary_id_, 0));
      done_ = true;
      fail("rename a temporary file to", error);
    }
    unregister_temporary_locked(std::exchange(temporary_id_, 0));
  }
  done_ = true;
}

void AtomicFile::discard() noexcept {
  if (done_) return;
  done_ = true;
  if (fd_ >= 0) ::close(std::exchange(fd_, -1));
  if (!temp_path_.empty()) {
    const std::lock_guard<std::mutex> lock(temporaries_lock());
    ::unlink(temp_path_.c_str());
    unregister_temporary_locked(std::exchange(temporary_id_, 0));
  }
}

void write_file(const std::string& who, const std::string& path,
                std::span<const std::uint8_t> bytes) {
  AtomicFile file(who, path);
  file.write_all(bytes);
  file.commit();
}

}  // namespace calder::output
