// SPDX-License-Identifier: MIT
#include "output_policy.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <mutex>
#include <system_error>
#include <utility>

#include "calder/error.hpp"
#include "calder/output_file.hpp"
#include "calder/render.hpp"
#include "errors.hpp"
#include "progress.hpp"

namespace calder::app {

namespace fs = std::filesystem;

namespace {

std::string system_message(int error) { return std::generic_category().message(error); }

// What a path names, for comparing outputs: an existing regular file by
// device and inode; a new file by its folder's device and inode and its name.
struct Identity {
  bool comparable = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::string name;  // "" for an existing file
};

Identity identity_of(const std::string& path) {
  Identity id;
  if (path.empty() || path == "-") return id;
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0) {
    if (!S_ISREG(info.st_mode) && !S_ISDIR(info.st_mode)) return id;  // devices, FIFOs
    id = {true, info.st_dev, info.st_ino, std::string()};
    return id;
  }
  const fs::path p(path);
  const std::string folder = p.has_parent_path() ? p.parent_path().string() : std::string(".");
  if (::stat(folder.c_str(), &info) != 0) return id;
  id = {true, info.st_dev, info.st_ino, p.filename().string()};
  return id;
}

bool same(const Identity& a, const Identity& b) {
  return a.comparable && b.comparable && a.device == b.device && a.inode == b.inode &&
         a.name == b.name;
}

// Whether `path` lies inside the folder `folder` (at any depth): the folders
// above it, as the kernel reached its parent (opened_path), compared by
// device and inode.
bool inside(const std::string& path, const Identity& folder) {
  // A folder not made yet holds nothing.
  if (!folder.comparable || !folder.name.empty() || path.empty() || path == "-") return false;
  const fs::path p(path);
  const std::string parent = p.has_parent_path() ? p.parent_path().string() : std::string(".");
  const int fd = ::open(parent.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return false;
  fs::path q = opened_path(fd);
  ::close(fd);
  for (; !q.empty(); q = q.parent_path()) {
    struct stat info {};
    if (::stat(q.c_str(), &info) == 0 && info.st_dev == folder.device &&
        info.st_ino == folder.inode) {
      return true;
    }
    if (q == q.root_path()) break;
  }
  return false;
}

std::string named(const NamedPath& p) { return p.flag + " " + quoted_path(p.path); }

// Whether `name` is a frame of a render: frame-NNNNNN.png (six or more digits).
bool is_frame_name(const std::string& name) {
  if (!name.starts_with("frame-") || !name.ends_with(".png")) return false;
  const std::string digits = name.substr(6, name.size() - 10);
  if (digits.size() < 6) return false;
  for (const char c : digits) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

mode_t current_umask() {
  const mode_t mask = ::umask(022);
  ::umask(mask);
  return mask;
}

}  // namespace

std::string shown_path(const std::string& path) { return detail::printable(path, 240); }

std::string quoted_path(const std::string& path) {
  std::string text(1, '\'');
  text += shown_path(path);
  text += '\'';
  return text;
}

void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs,
                   const std::optional<NamedPath>& frames) {
  std::vector<Identity> output_ids;
  for (const NamedPath& out : outputs) output_ids.push_back(identity_of(out.path));
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    for (const NamedPath& in : inputs) {
      if (same(output_ids[i], identity_of(in.path))) {
        throw InputError(named(outputs[i]) + ": is " + named(in) +
                         ", the input; refusing to overwrite it");
      }
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (same(output_ids[i], output_ids[j])) {
        throw InputError(named(outputs[i]) + ": is also " + named(outputs[j]) +
                         "; give each output its own file");
      }
    }
  }
  if (!frames) return;
  const Identity folder = identity_of(frames->path);
  const auto check_inside = [&](const NamedPath& p, const char* what) {
    if (same(identity_of(p.path), folder) || inside(p.path, folder)) {
      throw InputError(named(p) + ": is inside " + named(*frames) +
                       ", which the frames replace as a whole; " + what);
    }
  };
  for (const NamedPath& out : outputs) check_inside(out, "write it elsewhere");
  for (const NamedPath& in : inputs) check_inside(in, "keep the input elsewhere");
}

FrameFolder::FrameFolder(std::string dir) : dir_(std::move(dir)) {
  if (dir_.empty()) throw InputError("--png: the folder name is empty");
  const std::string shown = quoted_path(dir_);
  std::string as_given = dir_;  // "frames/" names "frames"; nothing else is rewritten
  while (as_given.size() > 1 && as_given.back() == '/') as_given.pop_back();
  const fs::path p(as_given);
  const std::string name = p.filename().string();
  if (name.empty() || name == "." || name == "..") {
    throw InputError("--png " + shown +
                     ": the frames replace the folder as a whole; name a folder of its own "
                     "(e.g. frames)");
  }
  struct stat old {};
  existed_ = ::lstat(p.c_str(), &old) == 0;
  const bool is_link = existed_ && S_ISLNK(old.st_mode);
  if (existed_) {
    const std::string why = foreign_owner_refusal(p.string());
    if (!why.empty()) throw InputError("--png " + shown + ": refusing to replace it: " + why);
    // Opened by the kernel, which follows a link with its own checks.
    const int fd = ::open(p.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) {
      const int error = errno;
      throw InputError(
          "--png " + shown + ": cannot write PNG frames there: " +
          (error == ENOTDIR ? std::string("it is not a directory") : system_message(error)));
    }
    ::fstat(fd, &old);
    target_ = is_link ? opened_path(fd) : p.string();
    ::close(fd);
    if (target_.empty()) {
      throw InputError("--png " + shown + ": the link can't be followed safely without /proc");
    }
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
        throw InputError("--png " + shown + ": cannot create the directory " +
                         quoted_path(it->string()) + ": " + reason);
      }
      created_.push_back(it->string());
    }
  }
  make_staging(existed_, existed_ ? &old : nullptr);
}

void FrameFolder::make_staging(bool existed, const struct stat* old) {
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
      throw InputError("--png " + quoted_path(dir_) + ": cannot write PNG frames there: " + reason);
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
    throw InputError("--png " + quoted_path(dir_) + ": cannot write PNG frames there: " + reason);
  }
  if (existed) carry_other_entries();
}

// The folder's other entries stay: files (and links, FIFOs, ...) are
// hard-linked into the staging folder now, folders are moved in by commit()
// just before the swap. The frames of an earlier render are not carried: the
// folder then holds this render's frames only.
void FrameFolder::carry_other_entries() {
  DIR* d = ::opendir(target_.c_str());
  if (d == nullptr) {
    const std::string reason = system_message(errno);
    discard();
    throw InputError("--png " + quoted_path(dir_) + ": cannot read the folder: " + reason);
  }
  std::string failed;
  int error = 0;
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name == "." || name == "..") continue;
    struct stat info {};
    if (::fstatat(::dirfd(d), e->d_name, &info, AT_SYMLINK_NOFOLLOW) != 0) continue;
    if (S_ISREG(info.st_mode) && is_frame_name(name)) continue;
    if (is_frame_name(name)) {  // a folder or a link where a frame goes
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
      throw InputError("--png " + quoted_path(dir_) + ": " + quoted_path(failed) +
                       " is not a PNG file of an earlier render; remove it or give another folder");
    }
    throw InputError("--png " + quoted_path(dir_) + ": cannot keep " + quoted_path(failed) +
                     " in the folder, which the frames replace as a whole (" +
                     system_message(error) + "); give a new folder");
  }
}

FrameFolder::~FrameFolder() {
  if (!committed_) discard();
  if (staging_fd_ >= 0) ::close(staging_fd_);
}

void FrameFolder::write(const Canvas& canvas, std::int64_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame-%06lld.png", static_cast<long long>(index));
  const auto failed = [&](const std::string& why) {
    const std::string message =
        "--png: cannot write " + quoted_path((fs::path(dir_) / name).string()) + ": " + why;
    if (names_.empty()) throw InputError(message);
    throw RunError(message);
  };
  std::vector<std::uint8_t> bytes;
  try {
    bytes = canvas.encode_png();
  } catch (const Error& e) {
    failed(e.what());
  }
  // Not flushed to disk one by one: commit() flushes the folder once.
  const int fd =
      ::openat(staging_fd_, name, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
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
  names_.emplace_back(name);
}

void FrameFolder::commit() {
  const std::function<void(const char*, int)> failed = [&](const char* what, int error) {
    throw RunError("--png " + quoted_path(dir_) + ": cannot " + what + ": " +
                   system_message(error));
  };
  // One flush for every frame, then the folder's entries.
  if (::syncfs(staging_fd_) != 0 || ::fsync(staging_fd_) != 0) failed("write the frames", errno);
  // From here to the swap the staging folder holds DIR's folders: the
  // interrupt watchdog waits (it takes this lock) rather than remove them.
  const std::lock_guard<std::mutex> lock(temporaries_lock());
  const char* from = staging_.c_str();
  const char* to = target_.c_str();
  move_folders(target_, staging_, failed);
  if (!existed_) {
    if (::rename(from, to) != 0) failed("move the frames into place", errno);
  } else if (::renameat2(AT_FDCWD, from, AT_FDCWD, to, RENAME_EXCHANGE) != 0) {
    // A file system without the exchange: the old folder steps aside first.
    if (errno != EINVAL && errno != ENOSYS) {
      const int error = errno;
      move_folders(staging_, target_, nullptr);
      failed("move the frames into place", error);
    }
    const std::string aside = staging_ + ".old";
    if (::rename(to, aside.c_str()) != 0) {
      const int error = errno;
      move_folders(staging_, target_, nullptr);
      failed("move the old frames aside", error);
    }
    if (::rename(from, to) != 0) {
      const int error = errno;
      (void)::rename(aside.c_str(), to);
      move_folders(staging_, target_, nullptr);
      failed("move the frames into place", error);
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
void FrameFolder::move_folders(const std::string& from, const std::string& to,
                               const std::function<void(const char*, int)>& failed) {
  for (std::size_t k = 0; k < folders_.size(); ++k) {
    const std::string a = from + "/" + folders_[k];
    const std::string b = to + "/" + folders_[k];
    if (::rename(a.c_str(), b.c_str()) != 0) {
      const int error = errno;
      for (std::size_t j = 0; j < k; ++j) {
        (void)::rename((to + "/" + folders_[j]).c_str(), (from + "/" + folders_[j]).c_str());
      }
      if (failed) failed("move a folder along", error);
      return;
    }
  }
}

// After the swap, the old folder: its frames and the entries carried (the same
// files as in the new one) are removed; anything else (made during the
// render) is moved into the new folder rather than lost.
void FrameFolder::clear_old(const std::string& old) noexcept {
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
      if (carried || (S_ISREG(info.st_mode) && is_frame_name(name))) {
        ::unlinkat(::dirfd(d), e->d_name, 0);
      } else if (::lstat(in_new.c_str(), &now) != 0) {
        (void)::rename((old + "/" + name).c_str(), in_new.c_str());
      }
    }
    ::closedir(d);
  }
  std::error_code ec;
  if (::rmdir(old.c_str()) != 0) fs::remove_all(old, ec);  // only old frames can be left
}

void FrameFolder::discard() noexcept {
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  if (temporary_id_ != 0) unregister_temporary(std::exchange(temporary_id_, 0));
  names_.clear();
  remove_created();
}

void FrameFolder::remove_created() noexcept {
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) ::rmdir(it->c_str());  // if empty
  created_.clear();
}

}  // namespace calder::app
