// SPDX-License-Identifier: MIT
// calder output module: a folder of files replaced as a whole
// (output.hpp, AtomicFolder).
#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <system_error>
#include <utility>

#include "calder/error.hpp"
#include "output.hpp"

namespace calder::output {

namespace fs = std::filesystem;

namespace {

std::string system_message(int error) { return std::generic_category().message(error); }

mode_t current_umask() {
  const mode_t mask = ::umask(022);
  ::umask(mask);
  return mask;
}

// Swaps two folders' names in one step where the system can (Linux's
// renameat2); false with errno EINVAL or ENOSYS where it can't.
bool exchange(const char* a, const char* b) {
#if defined(__linux__) && defined(RENAME_EXCHANGE)
  return ::renameat2(AT_FDCWD, a, AT_FDCWD, b, RENAME_EXCHANGE) == 0;
#else
  (void)a;
  (void)b;
  errno = ENOSYS;
  return false;
#endif
}

// Flushes the file system that holds the folder `fd` (Linux's syncfs, else
// the folder itself and each file's data by fsync of the folder: sync()).
bool flush_folder(int fd) {
#if defined(__linux__)
  return ::syncfs(fd) == 0 && ::fsync(fd) == 0;
#else
  ::sync();
  return ::fsync(fd) == 0;
#endif
}

}  // namespace

void AtomicFolder::refuse(const std::string& why) const {
  throw InputError(who_ + " " + quoted_path(dir_) + ": " + why);
}

void AtomicFolder::fail(const char* what, int error) const {
  throw RunError(who_ + " " + quoted_path(dir_) + ": cannot " + what + ": " +
                 system_message(error));
}

AtomicFolder::AtomicFolder(std::string who, std::string dir, Replaced replaced,
                           std::string replaced_kind)
    : who_(std::move(who)),
      dir_(std::move(dir)),
      replaced_(replaced),
      replaced_kind_(std::move(replaced_kind)) {
  if (dir_.empty()) throw InputError(who_ + ": the folder name is empty");
  std::string as_given = dir_;  // "frames/" names "frames"; nothing else is rewritten
  while (as_given.size() > 1 && as_given.back() == '/') as_given.pop_back();
  const fs::path p(as_given);
  const std::string name = p.filename().string();
  if (name.empty() || name == "." || name == "..") {
    refuse("its files replace the folder as a whole; name a folder of its own (e.g. frames)");
  }
  struct stat old {};
  existed_ = ::lstat(p.c_str(), &old) == 0;
  const bool is_link = existed_ && S_ISLNK(old.st_mode);
  if (existed_) {
    const std::string why = foreign_owner_refusal(p.string());
    if (!why.empty()) refuse("refusing to replace it: " + why);
    // Opened by the kernel, which follows a link with its own checks.
    const int fd = ::open(p.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) {
      const int error = errno;
      refuse("cannot write files there: " +
             (error == ENOTDIR ? std::string("it is not a directory") : system_message(error)));
    }
    ::fstat(fd, &old);
    target_ = is_link ? opened_path(fd) : p.string();
    ::close(fd);
    if (target_.empty()) refuse("the link can't be followed safely without /proc");
  } else {
    target_ = p.string();
    // The missing folders above DIR: created now (DIR itself appears at commit).
    std::vector<fs::path> missing;
    std::error_code ec;
    for (fs::path q = p.parent_path(); !q.empty() && !fs::exists(fs::symlink_status(q, ec));
         q = q.parent_path()) {
      missing.push_back(q);
      if (!q.has_parent_path() || q.parent_path() == q) break;
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
      if (::mkdir(it->c_str(), 0777) != 0) {
        const std::string reason = system_message(errno);
        remove_created();
        refuse("cannot create the directory " + quoted_path(it->string()) + ": " + reason);
      }
      created_.push_back(it->string());
    }
  }
  make_staging(existed_ ? &old : nullptr);
}

void AtomicFolder::make_staging(const void* old_stat) {
  const auto* old = static_cast<const struct stat*>(old_stat);
  const bool existed = old != nullptr;
  const fs::path target(target_);
  const std::string folder = target.has_parent_path() ? target.parent_path().string() : ".";
  std::string name = ".calder-frames." + target.filename().string();
  if (name.size() > 240) name.resize(240);
  std::string staging = folder + "/" + name + ".XXXXXX";
  {
    const std::lock_guard<std::mutex> lock(temporaries_lock());
    if (::mkdtemp(staging.data()) == nullptr) {
      const std::string reason =
          errno == ENOTDIR ? "a folder above it is not a directory" : system_message(errno);
      remove_created();
      refuse("cannot write files there: " + reason);
    }
    temporary_id_ = register_temporary(staging, true);
  }
  staging_ = staging;
  staging_fd_ = ::open(staging_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  // mkdtemp makes 0700: the folder gets the old one's mode (and owner, where
  // allowed), or a new folder's (0777 less the umask).
  const mode_t mode = existed ? (old->st_mode & 07777) : (0777 & ~current_umask());
  if (existed) (void)!::chown(staging_.c_str(), old->st_uid, old->st_gid);
  (void)::chmod(staging_.c_str(), mode);
  if (staging_fd_ < 0) {
    const std::string reason = system_message(errno);
    discard();
    refuse("cannot write files there: " + reason);
  }
  if (existed) carry_other_entries();
}

// The folder's other entries stay: files (and links, FIFOs, ...) are
// hard-linked into the staging folder now, folders are moved in by commit()
// just before the swap. The files `replaced` names (an earlier render's
// frames) are not carried: the folder then holds this run's only.
void AtomicFolder::carry_other_entries() {
  DIR* d = ::opendir(target_.c_str());
  if (d == nullptr) {
    const std::string reason = system_message(errno);
    discard();
    refuse("cannot read the folder: " + reason);
  }
  std::string failed;
  int error = 0;
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name == "." || name == "..") continue;
    struct stat info {};
    if (::fstatat(::dirfd(d), e->d_name, &info, AT_SYMLINK_NOFOLLOW) != 0) continue;
    if (S_ISREG(info.st_mode) && replaced_(name)) continue;
    if (replaced_(name)) {  // a folder or a link where a new file goes
      failed = name;
      error = EEXIST;
      break;
    }
    if (S_ISDIR(info.st_mode)) {
      folders_.push_back(name);
    } else if (::linkat(::dirfd(d), e->d_name, staging_fd_, e->d_name, 0) != 0) {
      failed = name;
      error = errno;
      break;
    }
  }
  ::closedir(d);
  if (!failed.empty()) {
    discard();
    if (error == EEXIST) {
      refuse(quoted_path(failed) + " is not " + replaced_kind_ +
             "; remove it or give another folder");
    }
    refuse("cannot keep " + quoted_path(failed) + " in the folder, which is replaced as a whole (" +
           system_message(error) + "); give a new folder");
  }
}

AtomicFolder::~AtomicFolder() {
  if (!committed_) discard();
  if (staging_fd_ >= 0) ::close(staging_fd_);
}

void AtomicFolder::write(const std::string& name, std::span<const std::uint8_t> bytes) {
  const auto failed = [&](const std::string& why) {
    const std::string message =
        who_ + ": cannot write " + quoted_path((fs::path(dir_) / name).string()) + ": " + why;
    if (names_.empty()) throw InputError(message);  // the first: a bad output, not a failed run
    throw RunError(message);
  };
  if (name.empty() || name.find('/') != std::string::npos) failed("not a file name");
  // Not flushed to disk one by one: commit() flushes the folder once.
  const int fd = ::openat(staging_fd_, name.c_str(),
                          O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) failed(system_message(errno));
  (void)::fchmod(fd, 0644);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int error = errno;
      ::close(fd);
      failed(system_message(error));
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0 && errno != EINTR) failed(system_message(errno));
  names_.push_back(name);
}

void AtomicFolder::commit() {
  const auto failed = [&](const char* what, int error) { fail(what, error); };
  // One flush for every file, then the folder's entries.
  if (!flush_folder(staging_fd_)) failed("write the files", errno);
  // From here to the swap the staging folder holds DIR's folders: the
  // interrupt watchdog waits (it takes this lock) rather than remove them.
  const std::lock_guard<std::mutex> lock(temporaries_lock());
  const char* from = staging_.c_str();
  const char* to = target_.c_str();
  move_folders(target_, staging_, true);
  if (!existed_) {
    if (::rename(from, to) != 0) failed("move the files into place", errno);
  } else if (!exchange(from, to)) {
    // A file system without the exchange: the old folder steps aside first.
    if (errno != EINVAL && errno != ENOSYS) {
      const int error = errno;
      move_folders(staging_, target_, false);
      failed("move the files into place", error);
    }
    const std::string aside = staging_ + ".old";
    if (::rename(to, aside.c_str()) != 0) {
      const int error = errno;
      move_folders(staging_, target_, false);
      failed("move the old files aside", error);
    }
    if (::rename(from, to) != 0) {
      const int error = errno;
      (void)::rename(aside.c_str(), to);
      move_folders(staging_, target_, false);
      failed("move the files into place", error);
    }
    staging_ = aside;
  }
  unregister_temporary_locked(std::exchange(temporary_id_, 0));
  if (existed_) clear_old(staging_);
  const fs::path target(target_);
  const std::string parent = target.has_parent_path() ? target.parent_path().string() : ".";
  const int parent_fd = ::open(parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (parent_fd >= 0) {
    (void)::fsync(parent_fd);
    ::close(parent_fd);
  }
  committed_ = true;
}

// Moves the carried folders from `from` into `to`; on a failure moves back
// those moved and calls `failed` (when given).
void AtomicFolder::move_folders(const std::string& from, const std::string& to, bool report) {
  for (std::size_t k = 0; k < folders_.size(); ++k) {
    const std::string a = from + "/" + folders_[k];
    const std::string b = to + "/" + folders_[k];
    if (::rename(a.c_str(), b.c_str()) != 0) {
      const int error = errno;
      for (std::size_t j = 0; j < k; ++j) {
        (void)::rename((to + "/" + folders_[j]).c_str(), (from + "/" + folders_[j]).c_str());
      }
      if (report) fail("move a folder along", error);
      return;
    }
  }
}

// After the swap, the old folder: its replaced files and the entries carried (the same
// files as in the new one) are removed; anything else (made during the
// render) is moved into the new folder rather than lost.
void AtomicFolder::clear_old(const std::string& old) noexcept {
  DIR* d = ::opendir(old.c_str());
  if (d != nullptr) {
    while (const dirent* e = ::readdir(d)) {
      const std::string name = e->d_name;
      if (name == "." || name == "..") continue;
      struct stat info {};
      struct stat now {};
      if (::fstatat(::dirfd(d), e->d_name, &info, AT_SYMLINK_NOFOLLOW) != 0) continue;
      const std::string in_new = target_ + "/" + name;
      const bool carried = ::lstat(in_new.c_str(), &now) == 0 && now.st_dev == info.st_dev &&
                           now.st_ino == info.st_ino;
      if (carried || (S_ISREG(info.st_mode) && replaced_(name))) {
        ::unlinkat(::dirfd(d), e->d_name, 0);
      } else if (::lstat(in_new.c_str(), &now) != 0) {
        (void)::rename((old + "/" + name).c_str(), in_new.c_str());
      }
    }
    ::closedir(d);
  }
  std::error_code ec;
  if (::rmdir(old.c_str()) != 0) fs::remove_all(old, ec);  // only old files can be left
}

void AtomicFolder::discard() noexcept {
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  if (temporary_id_ != 0) unregister_temporary(std::exchange(temporary_id_, 0));
  names_.clear();
  remove_created();
}

void AtomicFolder::remove_created() noexcept {
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) ::rmdir(it->c_str());  // if empty
  created_.clear();
}

}  // namespace calder::output
