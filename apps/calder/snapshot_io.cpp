// SPDX-License-Identifier: MIT
#include "snapshot_io.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

#include "calder/body_columns.hpp"
#include "calder/error.hpp"
#include "calder/snapshot.hpp"
#include "errors.hpp"
#include "parse.hpp"

namespace calder::app {

namespace {

std::int64_t parse_every(const std::string& text) {
  const std::optional<std::int64_t> k = to_int64(text);
  if (!k || *k < 1 || *k > max_frames) {
    throw InputError("--every: expected an integer from 1 to " + std::to_string(max_frames) +
                     ", got '" + detail::printable(text) + "'");
  }
  return *k;
}

// The first bytes of a file (fewer when it is shorter; none when unreadable).
Bytes first_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 8> head{};
  in.read(head.data(), head.size());
  const auto n = static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0));
  return {head.begin(), head.begin() + static_cast<std::ptrdiff_t>(n)};
}

// The flags that would change a resumed run: refused, the snapshot holds its own.
void refuse_scene_flags(const InputOptions& o, const std::string& file) {
  const std::pair<const char*, bool> flags[] = {
      {"--seed", o.seed.has_value()},
      {"--dt", o.dt.has_value()},
      {"--state", o.state.has_value()},
      {"--mouse", o.mouse.has_value()},
      {"--mouse-pressed", !o.mouse_pressed.empty()},
  };
  for (const auto& [flag, given] : flags) {
    if (given) {
      throw InputError(std::string(flag) + ": " + detail::printable(file, 240) +
                       " is a snapshot, which holds its own generator, time step, bodies and "
                       "mouse; a resumed run takes only --frames");
    }
  }
}

// A snapshot, or the archive's last snapshot at or before `frames` (its
// last one when frames is not given).
Simulation load_resumable(const std::string& path, std::optional<std::int64_t> frames) {
  if (!looks_like_archive(first_bytes(path))) return load_simulation(path);
  const ArchiveReader archive(path);
  for (std::size_t i = archive.size(); i-- > 0;) {
    if (!frames || archive.frame(i) <= *frames) return archive.simulation(i);
  }
  throw InputError(detail::printable(path, 240) +
                   (archive.size() == 0
                        ? std::string(": the archive holds no complete snapshot")
                        : ": no snapshot at or before frame " + std::to_string(*frames) +
                              " (the first is of frame " + std::to_string(archive.frame(0)) + ")"));
}

}  // namespace

void add_snapshot_options(CLI::App& command, SnapshotOptions& options) {
  command
      .add_option("--save", options.save,
                  "After the last frame, write a snapshot of the run to FILE (docs/SNAPSHOTS.md; "
                  "`calder run FILE` goes on from it bit for bit). Written to a temporary file "
                  "renamed on success")
      ->type_name("FILE");
  CLI::Option* archive =
      command
          .add_option("--archive", options.archive,
                      "Append a snapshot of the start, of every K-th frame (--every) and of the "
                      "last frame to the archive FILE, each flushed as written: a run killed "
                      "mid-way leaves the snapshots written so far readable")
          ->type_name("FILE");
  command
      .add_option("--every", options.every,
                  "With --archive: a snapshot every K frames, 1 to 10000000 (default 60)")
      ->type_name("K")
      ->needs(archive);
}

void check_snapshot_options(const SnapshotOptions& options, const std::string& /*source*/) {
  // Whether the paths are inputs or one another: output::check_outputs, with
  // the run's other outputs (snapshot_outputs_of).
  for (const auto& [flag, path] :
       {std::pair{"--save", &options.save}, std::pair{"--archive", &options.archive}}) {
    if (*path && ((*path)->empty() || **path == "-")) {
      throw InputError(std::string(flag) + ": give a file name (a snapshot is binary)");
    }
  }
  if (options.every) (void)parse_every(*options.every);
}

void add_snapshot_outputs(const SnapshotOptions& options, std::vector<output::NamedPath>& outputs) {
  if (options.save) outputs.push_back({"--save", *options.save});
  if (options.archive) outputs.push_back({"--archive", *options.archive, output::Kind::archive});
}

std::uint64_t snapshot_bytes_written(const SnapshotOptions& options, const Simulation& simulation,
                                     std::int64_t frames) {
  if (!options.save && !options.archive) return 0;
  // A snapshot is its body columns and a few kilobytes of the rest (the
  // scene, fields, mouse; 8 KiB is generous): estimated, never built just
  // to be measured.
  constexpr std::uint64_t columns = sizeof(BodyColumnsOf<char>);
  const std::uint64_t one =
      columns * 8 * static_cast<std::uint64_t>(simulation.world().body_count()) + (8U << 10U);
  std::uint64_t count = options.save ? 1 : 0;
  if (options.archive) {
    const std::int64_t every = options.every ? parse_every(*options.every) : default_archive_every;
    const std::int64_t start = simulation.frame();
    // The start, every K-th frame after it, and the last.
    count +=
        2 + static_cast<std::uint64_t>(std::max<std::int64_t>(frames / every - start / every, 0));
  }
  return count * (one + 64);  // a record's header and padding
}

SnapshotOutputs::SnapshotOutputs(const SnapshotOptions& options, const Simulation& simulation) {
  if (options.every) every_ = parse_every(*options.every);
  // Made now (the --save file's temporary; the archive opened, locked and
  // read), written only after the run: a bad path stops it before it starts.
  if (options.save) save_.emplace(*options.save);
  if (options.archive) {
    archive_ = std::make_unique<ArchiveWriter>(*options.archive);
    // A run going on from the archive's last snapshot doesn't repeat it.
    if (archive_->last_frame() != simulation.frame()) archive_->append(simulation);
    last_archived_ = simulation.frame();
  }
}

SnapshotOutputs::~SnapshotOutputs() {
  // A run that ends in an error leaves the archive as it was; one stopped by
  // a signal keeps the snapshots written so far (with their index).
  if (archive_ && output::InterruptScope::signal() == 0) archive_->abandon();
}

void SnapshotOutputs::after_frame(const Simulation& simulation) {
  if (archive_ && simulation.frame() % every_ == 0) {
    archive_->append(simulation);
    last_archived_ = simulation.frame();
  }
}

void SnapshotOutputs::finish(const Simulation& simulation) {
  if (archive_) {
    if (last_archived_ != simulation.frame()) archive_->append(simulation);
    archive_->close();
  }
  if (save_) {
    const Bytes bytes = to_snapshot(simulation);
    save_->stream().write(reinterpret_cast<const char*>(bytes.data()),
                          static_cast<std::streamsize>(bytes.size()));
    save_->commit();
  }
}

bool names_snapshot(const std::string& argument) {
  // Only a regular file is looked into: a FIFO's first bytes are the scene
  // reader's (and opening one would wait for a writer).
  std::error_code ec;
  if (!std::filesystem::is_regular_file(argument, ec)) return false;
  const Bytes head = first_bytes(argument);
  return looks_like_snapshot(head) || looks_like_archive(head);
}

PreparedInput prepare_resume(const InputOptions& options) {
  refuse_scene_flags(options, options.scene);
  std::optional<std::int64_t> frames;
  if (options.frames) frames = parse_frames("--frames", *options.frames);
  Simulation simulation = load_resumable(options.scene, frames);
  if (frames && *frames < simulation.frame()) {
    throw InputError("--frames " + std::to_string(*frames) + ": " +
                     detail::printable(options.scene, 240) + " is at frame " +
                     std::to_string(simulation.frame()) +
                     " already (--frames counts from the scene's start)");
  }
  PreparedInput input;
  input.source = options.scene;
  input.scene = simulation.scene();
  // The run's end, which a snapshot saved from it keeps: --frames, or the
  // scene's frames (those of the run that saved it), and not before the snapshot.
  input.scene.frames = frames ? *frames : std::max(input.scene.frames, simulation.frame());
  // The same caps as a scene file's: a snapshot's thread counts as the
  // processors allow (the scene's, and the world's as it is now).
  limit_threads(input.scene, input.source);
  World world = simulation.world();
  world.set_threads(std::min(world.threads(), usable_threads()));
  for (std::size_t k = 0; k < world.fields().size(); ++k) {
    if (auto* mutual = std::get_if<MutualAttraction>(&world.field(k))) {
      mutual->threads = std::min(mutual->threads, std::max(usable_threads(), 1));
    }
  }
  simulation = Simulation(input.scene, std::move(world), simulation.progress());
  if (!options.no_work_limit) {
    Scene rest = input.scene;
    rest.frames -= simulation.frame();
    check_work_budget(rest, simulation.world().body_count(), input.source);
  }
  input.resumed.emplace(std::move(simulation));
  return input;
}

std::string save_window_snapshot(const Simulation& simulation, const std::string& stem) {
  const std::string path = stem + "-" + std::to_string(simulation.frame()) + ".snap";
  save_snapshot(simulation, path);  // an output::AtomicFile
  return path;
}

}  // namespace calder::app
