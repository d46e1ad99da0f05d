// SPDX-License-Identifier: MIT
// calder output module: the output policy (output.hpp), for one path
// (probe) and for all the outputs of a run (check_outputs).
#include "policy.hpp"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <system_error>
#include <vector>

#include "calder/error.hpp"
#include "output.hpp"

#ifndef O_PATH  // (a system without it: a read-only open finds the folder as well)
#define O_PATH O_RDONLY
#endif

namespace calder::output {

namespace fs = std::filesystem;

namespace {

std::string directory_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
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

bool folder_status(const std::string& path, struct stat& info) {
  const std::string dir = directory_of(path);
  return ::stat(dir.empty() ? "." : dir.c_str(), &info) == 0;
}

std::string system_message(int error) { return std::generic_category().message(error); }

}  // namespace

std::string shown_path(const std::string& path) { return calder::detail::printable(path, 240); }

std::string quoted_path(const std::string& path) {
  std::string text(1, '\'');
  text += shown_path(path);
  text += '\'';
  return text;
}

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

namespace detail {

std::string prefix(const std::string& who) { return who.empty() ? std::string() : who + ": "; }

namespace {

[[noreturn]] void refuse(const std::string& who, const std::string& path, const std::string& why) {
  throw InputError(prefix(who) + "refusing to write " + quoted_path(path) + ": " + why);
}

[[noreturn]] void cannot(const std::string& who, const std::string& path, const std::string& why) {
  throw InputError(prefix(who) + "cannot write " + quoted_path(path) + ": " + why);
}

// What the policy makes of a path that the kernel did not open for writing
// (`error`): a FIFO without a reader, a folder, a write-protected file, a
// new file (its folder must exist), a link to nothing.
Probe probe_unopened(const std::string& who, const std::string& path, bool is_link, int error,
                     bool open_direct) {
  Probe p;
  p.target = path;
  if (error == ENXIO) {  // a FIFO without a reader yet
    p.what = Probe::What::direct;
    p.waits = true;
    if (open_direct) {
      p.fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
      if (p.fd < 0) cannot(who, path, system_message(errno));
    }
    return p;
  }
  if (error == EISDIR) {
    p.what = Probe::What::folder;
    (void)::stat(path.c_str(), &p.info);
    return p;
  }
  struct stat info {};
  if ((error == EACCES || error == EPERM) && ::stat(path.c_str(), &info) == 0 &&
      S_ISREG(info.st_mode)) {
    refuse(who, path,
           "it is write-protected (the system refuses us write access, as the shell's > would)");
  }
  if (error != ENOENT) cannot(who, path, system_message(error));
  if (is_link) refuse(who, path, "it is a symbolic link to a missing file");
  struct stat folder {};
  if (!folder_status(path, folder)) {
    throw InputError(prefix(who) + shown_path(path) + ": cannot create the file: the folder " +
                     quoted_path(directory_of(path)) + " does not exist");
  }
  if (!S_ISDIR(folder.st_mode)) cannot(who, path, "a folder above it is not a directory");
  return p;
}

}  // namespace

// Nothing is resolved by hand: the path is opened by the kernel, which
// follows links with its own checks, and what it opened decides the rest.
Probe probe(const std::string& who, const std::string& path, bool open_direct) {
  if (path.empty() || path.back() == '/') {
    struct stat folder {};
    if (!path.empty() && ::stat(path.c_str(), &folder) == 0 && S_ISDIR(folder.st_mode)) {
      throw InputError(prefix(who) + shown_path(path) + ": is a directory, not a file");
    }
    throw InputError(prefix(who) + "not a file name: " + quoted_path(path));
  }
  Probe p;
  struct stat link {};
  const bool is_link = ::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode);
  if (is_link) {
    const std::string why = foreign_owner_refusal(path);
    if (!why.empty()) refuse(who, path, why);
  }
  // A FIFO is only looked at when not written now: opening and closing it
  // would end its reader's input.
  struct stat status {};
  if (!open_direct && ::stat(path.c_str(), &status) == 0 && S_ISFIFO(status.st_mode)) {
    p.what = Probe::What::direct;
    p.target = path;
    p.info = status;
    return p;
  }
  // Opened for writing, never created and never truncated: the kernel says
  // whether we may write it (permissions, fs.protected_symlinks) and what it is.
  const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) return probe_unopened(who, path, is_link, errno, open_direct);
  if (::fstat(fd, &p.info) != 0) {
    const int error = errno;
    ::close(fd);
    cannot(who, path, system_message(error));
  }
  p.target = path;
  if (!S_ISREG(p.info.st_mode) || names_a_descriptor(path)) {
    if (S_ISBLK(p.info.st_mode)) {
      ::close(fd);
      throw InputError(prefix(who) + "refusing to write to the block device " + quoted_path(path));
    }
    // A FIFO, a character device (/dev/null, a terminal), a socket, or a
    // descriptor's file (/dev/stdout): written directly, in order.
    p.what = Probe::What::direct;
    if (open_direct) {
      const int flags = ::fcntl(fd, F_GETFL);
      (void)::fcntl(fd, F_SETFL, (flags & ~O_NONBLOCK) | (S_ISREG(p.info.st_mode) ? O_APPEND : 0));
      p.fd = fd;
    } else {
      ::close(fd);
    }
    return p;
  }
  p.what = Probe::What::regular;
  p.target = is_link ? opened_path(fd) : path;
  ::close(fd);
  if (p.target.empty()) refuse(who, path, "the link can't be followed safely without /proc");
  if ((p.info.st_mode & 0222) == 0) {
    refuse(who, path, "it is write-protected (no write permission for anyone)");
  }
  const std::string why = foreign_owner_refusal(p.target);
  if (!why.empty()) refuse(who, path, why);
  return p;
}

}  // namespace detail

namespace {

// What a path names, for comparing outputs: an existing regular file or
// folder by device and inode; a new file by its folder's and its name.
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
  // A link to nothing names the file it would create.
  fs::path p(path);
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(p, ec))) {
    const fs::path to = fs::read_symlink(p, ec);
    if (!ec) p = to.is_absolute() ? to : p.parent_path() / to;
  }
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
// above it, as the kernel reached its parent, compared by device and inode.
bool inside(const std::string& path, const Identity& folder) {
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

// The policy for one output, applied without creating anything.
void check_one(const NamedPath& out) {
  if (out.path == "-" && out.kind == Kind::file) return;
  if (out.kind == Kind::folder) {
    const std::string why = foreign_owner_refusal(out.path);
    if (!why.empty()) {
      throw InputError(out.flag + " " + quoted_path(out.path) + ": refusing to replace it: " + why);
    }
    std::error_code ec;
    const fs::file_status s = fs::status(out.path, ec);
    if (fs::exists(s) && !fs::is_directory(s)) {
      throw InputError(out.flag + " " + quoted_path(out.path) +
                       ": cannot write files there: it is not a directory");
    }
    return;
  }
  const detail::Probe p = detail::probe(out.flag, out.path, false);
  if (p.what == detail::Probe::What::folder) {
    throw InputError(out.flag + ": " + shown_path(out.path) + ": is a directory, not a file");
  }
  if (out.kind == Kind::archive && p.what == detail::Probe::What::direct) {
    throw InputError(out.flag + ": refusing to write " + quoted_path(out.path) +
                     ": an archive must be a regular file (it is read back, then appended to)");
  }
}

}  // namespace

void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (const NamedPath& out : outputs) check_one(out);
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
  for (std::size_t f = 0; f < outputs.size(); ++f) {
    if (outputs[f].kind != Kind::folder) continue;
    const NamedPath& frames = outputs[f];
    const Identity folder = identity_of(frames.path);
    const auto check_inside = [&](const NamedPath& p, const char* what) {
      if (same(identity_of(p.path), folder) || inside(p.path, folder)) {
        throw InputError(named(p) + ": is inside " + named(frames) +
                         ", which is replaced as a whole; " + what);
      }
    };
    for (std::size_t k = 0; k < outputs.size(); ++k) {
      if (k != f) check_inside(outputs[k], "write it elsewhere");
    }
    for (const NamedPath& in : inputs) check_inside(in, "keep the input elsewhere");
  }
}

}  // namespace calder::output
