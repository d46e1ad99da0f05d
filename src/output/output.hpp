// SPDX-License-Identifier: MIT
// calder: every file calder writes goes through here (src/output/, part of
// the core library): the output policy, the three ways of writing, the
// registry of temporaries and the handling of terminating signals.
//
// The policy (apps/README.md, "Output files"). A path is opened by the kernel
// (never created, never truncated, to look), which follows links with its
// own checks (permissions, fs.protected_symlinks); what it opened decides:
//   - nothing yet: a new file, made whole beside it (AtomicFile);
//   - a regular file: replaced whole (AtomicFile, keeping its mode and owner
//     where allowed) or appended to (AppendFile); through a symbolic link,
//     the file the kernel reached, the link stays. Refused: a file we may not
//     write, a file without any write permission (0444, even for root), a
//     file or link another user owns in a sticky folder (/tmp) unless the
//     folder is theirs, a link to nothing;
//   - a FIFO, a character device (/dev/null, a terminal), a socket, or a path
//     naming an open descriptor (/dev/stdout, /dev/fd/N): written directly,
//     in order (AtomicFile only; an archive must be a regular file);
//   - a directory (except for AtomicFolder) or a block device: refused.
// check_outputs() applies it to every output of a run at once, together with
// the rule that no output is an input or another output, before anything is
// created or truncated.
//
// Refusals and files that can't be created throw calder::InputError; a write
// that fails once writing began throws calder::RunError. Both name the path,
// the operation and the system's reason: "cannot write 'out.csv': No space
// left on device". Paths in messages are escaped (detail::printable).
#pragma once

#include <signal.h>
#include <array>

#include <csignal>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

namespace calder::output {

// --- the policy, for all outputs of a run -------------------------------------

// What an output is written as (how check_outputs treats it).
enum class Kind {
  file,     // AtomicFile: replaced whole, or written directly (a FIFO, "-")
  folder,   // AtomicFolder: replaced whole; nothing else may lie inside it
  archive,  // AppendFile: appended to; must be a regular file
};

// A path as given, with the flag (or argument) that named it.
struct NamedPath {
  std::string flag;  // "--trajectory", "the scene file", ...
  std::string path;
  Kind kind = Kind::file;
};

// Throws InputError (exit 2, one line naming the flags and paths) when the
// policy refuses an output (checked without creating or truncating
// anything), when an output is an input or another output (existing files by
// device and inode, new ones by folder and name), or when an input or
// another output lies inside a folder output. "-", devices and FIFOs are not
// compared.
void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

// Why the policy refuses to write through what `path` names ("" when it
// doesn't): a symbolic link, file or folder that another user than us and the
// folder's owner owns in a sticky folder (/tmp).
std::string foreign_owner_refusal(const std::string& path);

// The path the kernel reached when it opened `fd`, from /proc/self/fd; ""
// where /proc is not mounted.
std::string opened_path(int fd);

// A path as shown in messages (control characters escaped, long paths cut),
// and the same in single quotes.
std::string shown_path(const std::string& path);
std::string quoted_path(const std::string& path);

// --- an atomic file ---------------------------------------------------------------

// A file that appears whole or not at all. A new or regular file is written
// to a temporary ".<name>.tmp-XXXXXX" in the target's folder (made by
// mkostemp: O_CREAT | O_EXCL, so never through a link; registered for the
// signal handler as it is made), which commit() flushes to disk (fsync) and
// renames over the target; a new file gets 0644 whatever the umask. Destroyed
// without commit() it removes the temporary: the target is untouched. A
// FIFO, a character device or a descriptor's path is written directly.
class AtomicFile {
 public:
  // `who` prefixes messages ("Canvas::write_png"; empty: no prefix).
  AtomicFile(std::string who, std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // The open descriptor (-1 once committed or discarded); whoever needs
  // their own (giflib closes the one it is given) dup()s it.
  [[nodiscard]] int fd() const { return fd_; }
  // Writes all bytes (retrying short writes); throws RunError and removes the
  // temporary on the first failure.
  void write_all(const void* data, std::size_t size);
  void write_all(std::span<const std::uint8_t> bytes) { write_all(bytes.data(), bytes.size()); }
  // Flushes to disk and renames over the target (closes a direct file).
  void commit();
  // Removes the temporary now (idempotent, never throws).
  void discard() noexcept;

  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const std::string& temp_path() const { return temp_path_; }
  [[nodiscard]] bool direct() const { return direct_; }
  // The errno of the first failed write (0: none).
  [[nodiscard]] int write_error() const { return error_; }
  // Throws RunError("<who>: cannot <what> '<path>': <strerror(error)>").
  [[noreturn]] void fail(const char* what, int error) const;

 private:
  std::string who_;
  std::string path_;
  std::string target_;  // path_ with symbolic links followed
  std::string temp_path_;
  std::size_t temporary_id_ = 0;
  int fd_ = -1;
  int error_ = 0;
  bool direct_ = false;
  bool done_ = false;
};

// Writes `bytes` to `path` as an AtomicFile (committed).
void write_file(const std::string& who, const std::string& path,
                std::span<const std::uint8_t> bytes);

// --- an atomic folder -------------------------------------------------------------

// A folder of files replaced as a whole (the PNG frames of a render). Files
// are written to a staging folder beside DIR (".calder-frames.NAME.XXXXXX",
// registered for the signal handler), and commit() flushes them to disk once
// (syncfs) and swaps the staging folder into place (renameat2
// RENAME_EXCHANGE; a rename when DIR is new): the new files appear together,
// the old ones go together. DIR's other entries stay: its files are
// hard-linked into the staging folder at the start, its folders moved in just
// before the swap; the old files that `replaced` names are not carried.
// Without commit() the staging folder and the folders created above DIR are
// removed: DIR stays as it was. DIR may not be "." or "..".
class AtomicFolder {
 public:
  // Which of DIR's entries the new files replace, and what they are called in
  // messages ("a PNG file of an earlier render").
  using Replaced = bool (*)(const std::string& name);
  // `who` names the folder in messages ("--png"). Throws InputError.
  AtomicFolder(std::string who, std::string dir, Replaced replaced, std::string replaced_kind);
  ~AtomicFolder();
  AtomicFolder(const AtomicFolder&) = delete;
  AtomicFolder& operator=(const AtomicFolder&) = delete;

  // Writes the file `name` (no '/') into the staging folder; throws RunError
  // naming DIR/name on failure. Not flushed one by one: commit() flushes once.
  void write(const std::string& name, std::span<const std::uint8_t> bytes);
  // Flushes and swaps into place; throws RunError (DIR then holds what it
  // held before).
  void commit();

  [[nodiscard]] std::size_t count() const { return names_.size(); }
  [[nodiscard]] const std::string& dir() const { return dir_; }
  [[nodiscard]] const std::string& name(std::size_t k) const { return names_.at(k); }
  [[nodiscard]] const std::string& staging() const { return staging_; }

 private:
  void discard() noexcept;
  void remove_created() noexcept;
  void make_staging(const void* old_stat);
  void carry_other_entries();
  void move_folders(const std::string& from, const std::string& to, bool report);
  void clear_old(const std::string& old) noexcept;
  [[noreturn]] void refuse(const std::string& why) const;
  [[noreturn]] void fail(const char* what, int error) const;

  std::string who_;
  std::string dir_;
  std::string target_;
  std::string staging_;
  Replaced replaced_;
  std::string replaced_kind_;
  int staging_fd_ = -1;
  std::size_t temporary_id_ = 0;
  bool existed_ = false;
  std::vector<std::string> created_;
  std::vector<std::string> folders_;
  std::vector<std::string> names_;
  bool committed_ = false;
};

// --- an appendable file -----------------------------------------------------------

// A regular file appended to under an exclusive lock (flock, held while the
// object lives: a second writer is refused at once), that can be put back as
// it was. A new file is created with O_CREAT | O_EXCL | O_NOFOLLOW (0644); an
// existing one is opened by the policy above (links followed by the kernel;
// FIFOs, devices and folders refused). Nothing is written before the first
// write_at/append; rollback() (and the destructor, unless keep() was called)
// restores the original length and the bytes given to save_tail(), or
// removes a file it created.
class AppendFile {
 public:
  // Throws InputError: refused, locked by another writer, can't be created.
  AppendFile(std::string who, std::string path);
  ~AppendFile();
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;

  [[nodiscard]] int fd() const { return fd_; }
  [[nodiscard]] bool created() const { return created_; }
  // The file's length when opened.
  [[nodiscard]] std::uint64_t original_size() const { return original_size_; }
  // Reads `size` bytes at `offset` (fewer at the end of the file).
  [[nodiscard]] std::vector<std::uint8_t> read_at(std::uint64_t offset, std::size_t size) const;
  // Cuts the file to `length` <= original_size() (what follows is kept for
  // rollback) and appends from there.
  void cut_to(std::uint64_t length);
  // Appends; throws RunError on failure.
  void append(std::span<const std::uint8_t> bytes);
  // Flushes to disk (fsync); throws RunError on failure.
  void sync();
  // From now on the destructor keeps what was written.
  void keep() noexcept { kept_ = true; }
  // Puts the file back as it was when opened (never throws).
  void rollback() noexcept;
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const char* what, int error) const;
  std::string who_;
  std::string path_;
  std::string target_;
  std::vector<std::uint8_t> tail_;  // the bytes after the cut, for rollback
  std::uint64_t original_size_ = 0;
  std::uint64_t cut_ = 0;
  std::uint64_t end_ = 0;
  int fd_ = -1;
  bool created_ = false;
  bool kept_ = false;
  bool touched_ = false;
};

// --- temporaries and signals ------------------------------------------------------

// The signals that end a job and can be caught.
constexpr std::array<int, 9> terminating_signals = {SIGINT,  SIGTERM, SIGHUP,  SIGQUIT, SIGPIPE,
                                                    SIGXFSZ, SIGALRM, SIGUSR1, SIGUSR2};
// How long a job may take to stop by itself after a terminating signal.
constexpr int interrupt_grace_ms = 400;

// The registry of what must be removed if the process is stopped (a temporary
// file; a staging folder with what is inside it). AtomicFile and AtomicFolder
// register theirs; a path is registered while temporaries_lock() is held
// across its creation, so that the signal handler's watchdog never races a
// file being created.
std::mutex& temporaries_lock();
std::size_t register_temporary(const std::string& path, bool folder);  // lock held
void unregister_temporary(std::size_t id);
void unregister_temporary_locked(std::size_t id);
// Removes every registered temporary now (the lock held by the caller).
void remove_temporaries_locked() noexcept;

// The one handler of terminating signals. While an InterruptScope lives, each
// terminating signal (not ignored at start) only records itself: the job's
// loops call signal() (0: none) and stop cleanly, their destructors removing
// their temporaries. A job that has not stopped interrupt_grace_ms after the
// signal is ended by the scope's watchdog thread: it removes the registered
// temporaries, prints "<program>: interrupted" (nothing for SIGPIPE) and exits
// 128 + the signal. Scopes nest (the innermost restores the outer's).
class InterruptScope {
 public:
  explicit InterruptScope(std::string program = "calder");
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

  // The signal received since the scope began (0: none).
  [[nodiscard]] static int signal() noexcept;

 private:
  struct Watchdog;
  std::unique_ptr<Watchdog> watchdog_;
  std::array<struct sigaction, terminating_signals.size()> old_{};
};

}  // namespace calder::output
