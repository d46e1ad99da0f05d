// SPDX-License-Identifier: MIT
// calder command: snapshots (calder/snapshot.hpp, docs/SNAPSHOTS.md).
//
//   calder run example-2.7 --frames 300 --save run.snap    stop at frame 300, saved
//   calder run run.snap --frames 600                         go on to frame 600
//   calder run rain --archive rain.archive --every 60       a snapshot every 60 frames
//   calder run rain.archive --frames 900                     on from its last snapshot
//   calder run rain.archive --frames 130                     on from the one of frame 120
//   calder window run.snap                                   open it in the window
//
// A SCENE|FILE argument that is a snapshot or an archive (its first bytes
// say so) resumes the run it holds: --frames is then the frame to run to,
// counted from the scene's start like every frame number; the flags that
// would change the run (--seed, --dt, --state, --mouse, --mouse-pressed)
// are refused, since the snapshot holds its own.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "../../src/output/output.hpp"
#include "calder/scene.hpp"
#include "calder/snapshot.hpp"
#include "output_file.hpp"
#include "run_options.hpp"

namespace CLI {
class App;
}

namespace calder::app {

// --archive writes at most this many snapshots (--every's default: 60).
constexpr std::int64_t default_archive_every = 60;

struct SnapshotOptions {
  std::optional<std::string> save;     // --save FILE
  std::optional<std::string> archive;  // --archive FILE
  std::optional<std::string> every;    // --every K
};

// Adds --save, --archive and --every to a verb (calder run).
void add_snapshot_options(CLI::App& command, SnapshotOptions& options);
// Checks the flags before anything is read. Throws InputError naming the flag.
void check_snapshot_options(const SnapshotOptions& options, const std::string& source);
// Adds --save and --archive to the outputs of a run (checked together by
// output::check_outputs).
void add_snapshot_outputs(const SnapshotOptions& options, std::vector<output::NamedPath>& outputs);
// The bytes the snapshots of a run to `frames` will write (for the budget).
std::uint64_t snapshot_bytes_written(const SnapshotOptions& options, const Simulation& simulation,
                                     std::int64_t frames);

// The snapshot outputs of one run, made once every check passed: the
// --save file's temporary, the archive opened (locked, its records read) and
// the start appended. Destroyed without finish() after an error, the archive
// is put back as it was (one stopped by a signal keeps what was appended).
class SnapshotOutputs {
 public:
  SnapshotOutputs(const SnapshotOptions& options, const Simulation& simulation);
  ~SnapshotOutputs();
  SnapshotOutputs(const SnapshotOutputs&) = delete;
  SnapshotOutputs& operator=(const SnapshotOutputs&) = delete;
  // After each frame: the archive's snapshot of every K-th frame.
  void after_frame(const Simulation& simulation);
  // After the last frame: its snapshot in the archive (unless there), the
  // archive's index, and the --save file. Throws RunError when a write fails.
  void finish(const Simulation& simulation);

 private:
  std::optional<OutputFile> save_;
  std::unique_ptr<ArchiveWriter> archive_;
  std::int64_t every_ = default_archive_every;
  std::int64_t last_archived_ = -1;
};

// Whether the SCENE|FILE argument names a snapshot or an archive file.
bool names_snapshot(const std::string& argument);
// The input of a run resumed from a snapshot, or from an archive's last
// snapshot at or before --frames (its last without --frames): its scene
// (frames: --frames, or else the scene's, i.e. those of the run that saved
// it, at least the snapshot's frame), no seed or state.
// Throws InputError naming the file or the refused flag.
PreparedInput prepare_resume(const InputOptions& options);

// The window's key: writes `stem`-FRAME.snap in the current folder and
// returns its name. Throws calder::Error when the write fails.
std::string save_window_snapshot(const Simulation& simulation, const std::string& stem);

}  // namespace calder::app
