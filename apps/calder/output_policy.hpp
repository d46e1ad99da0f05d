// SPDX-License-Identifier: MIT
// calder command: the output policy, in one place (apps/README.md, "Output
// files"):
//   - each output file is opened by calder::OutputFile (calder/output_file.hpp):
//     what is replaced, what is written directly, what is refused;
//   - check_outputs(): before anything is written, no output may be one of the
//     run's inputs (the scene file, the --state file) or another of its
//     outputs, nor lie inside the folder of PNG frames;
//   - FrameFolder: the PNG frames of a render, staged beside their folder and
//     swapped into place as a whole (all or none), one flush to disk a render.
// Paths in messages are shown escaped (shown_path), as in every error.
#pragma once

#include <sys/stat.h>
#include <sys/types.h>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace calder {
class Canvas;
}

namespace calder::app {

// A path as given with the flag (or argument) that named it.
struct NamedPath {
  std::string flag;  // "--trajectory", "the scene file", ...
  std::string path;
};

// A path as shown in any message and report: control characters escaped,
// long paths cut (calder::detail::printable, as the errors' one_line does);
// quoted_path adds single quotes.
std::string shown_path(const std::string& path);
std::string quoted_path(const std::string& path);

// Throws InputError (exit 2, one line naming both) when an output is the same
// file as an input or as another output (existing files by device and inode,
// new ones by folder and name), or when an input or another output lies
// inside `frames` (the --png folder, replaced as a whole). "-", devices and
// FIFOs are not compared.
void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs,
                   const std::optional<NamedPath>& frames);

// The folder of PNG frames DIR/frame-000000.png, ... Frames are written to a
// staging folder beside DIR (".calder-frames.NAME.XXXXXX"), and commit()
// flushes them to disk once (syncfs) and swaps the staging folder into place
// (renameat2 RENAME_EXCHANGE; a rename when DIR is new): the new frames appear
// together and the old ones go together. DIR's other entries stay: its files
// are hard-linked into the staging folder at the start, its folders moved in
// just before the swap. Without commit() (a failure, a signal) the staging
// folder and the folders created above DIR are removed: DIR stays as it was.
// DIR may not be "." or "..", which can't be swapped.
class FrameFolder {
 public:
  // Throws InputError naming DIR when it can't be used.
  explicit FrameFolder(std::string dir);
  ~FrameFolder();
  FrameFolder(const FrameFolder&) = delete;
  FrameFolder& operator=(const FrameFolder&) = delete;

  // Writes frame-<index>.png into the staging folder. A failure on the first
  // frame is bad output (exit 2); later ones are a failed run (exit 1).
  void write(const Canvas& canvas, std::int64_t index);
  // Flushes and swaps the frames into place; throws RunError on failure
  // (DIR then holds what it held before).
  void commit();

  [[nodiscard]] std::size_t count() const { return names_.size(); }
  [[nodiscard]] const std::string& dir() const { return dir_; }
  [[nodiscard]] const std::string& name(std::size_t k) const { return names_.at(k); }
  [[nodiscard]] const std::string& staging() const { return staging_; }

 private:
  void discard() noexcept;
  void remove_created() noexcept;
  void make_staging(bool existed, const struct stat* old);
  void carry_other_entries();
  void move_folders(const std::string& from, const std::string& to,
                    const std::function<void(const char*, int)>& failed);
  void clear_old(const std::string& old) noexcept;

  std::string dir_;     // as given
  std::string target_;  // the folder replaced (links followed by the kernel)
  std::string staging_;
  int staging_fd_ = -1;
  std::size_t temporary_id_ = 0;
  bool existed_ = false;
  std::vector<std::string> created_;  // missing folders above DIR, outermost first
  std::vector<std::string> folders_;  // DIR's folders, moved along at commit
  std::vector<std::string> names_;    // staged frames
  bool committed_ = false;
};

}  // namespace calder::app
