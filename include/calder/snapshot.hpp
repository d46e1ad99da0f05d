// SPDX-License-Identifier: MIT
// calder: snapshots, a run stopped and continued bit for bit; archives, a
// snapshot every few frames in one file.
//
// A snapshot holds everything a Simulation needs to go on as if it had never
// stopped: the scene (its fields, body groups, scripted input, look), the
// world's settings and clock, every body column, the fields as they are now
// (a dragged attractor, an accumulated noise offset, a wind turned on), the
// random generator's and the noise's state, the frame counter and the mouse.
// Stepping a loaded snapshot M frames gives the same bits as stepping the
// original, for every scene (tests/test_snapshot.cpp). A World alone can be
// saved too (no scene, no frame counter).
//
//   calder::save_snapshot(simulation, "run.snap");
//   calder::Simulation resumed = calder::load_simulation("run.snap");
//
// The format is docs/SNAPSHOTS.md's (numpy reads it without calder). A file
// that is truncated, corrupted, of another version or not a snapshot is
// refused with an InputError whose one line names the file and what is wrong.
//
// A world holding C++ code (a CustomForce field, an AttractionLaw with a
// custom function) can't be saved: save throws calder::Error naming the field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "calder/scene.hpp"
#include "calder/world.hpp"

namespace calder {

namespace output {
class AppendFile;  // the output policy's appendable file (src/output/)
}  // namespace output

// The newest format version; every version from 1 to it is read. A snapshot
// is written as version 1 unless it holds an adaptive integrator's state
// (section ADPT, version 2), so that what version 1 could hold stays
// readable by a calder that reads only version 1.
inline constexpr std::uint32_t kSnapshotVersion = 2;
// The archive format's version (the snapshots inside carry their own).
inline constexpr std::uint32_t kArchiveVersion = 1;

using Bytes = std::vector<std::uint8_t>;

// The largest snapshot read (a file, or one record of an archive): a world of
// max_bodies bodies takes 800 MB.
inline constexpr std::uint64_t max_snapshot_bytes = std::uint64_t{2} << 30;

// --- snapshots in memory ---
[[nodiscard]] Bytes to_snapshot(const Simulation& simulation);
[[nodiscard]] Bytes to_snapshot(const World& world);
// `source` names the bytes in messages (a file name). A simulation needs a
// snapshot of a simulation; a world can be read from either.
[[nodiscard]] Simulation simulation_from_snapshot(std::span<const std::uint8_t> bytes,
                                                  const std::string& source);
[[nodiscard]] World world_from_snapshot(std::span<const std::uint8_t> bytes,
                                        const std::string& source);

// What a snapshot holds, read from its sections without building a world.
struct SnapshotInfo {
  bool has_scene = false;  // a Simulation's snapshot
  std::string scene;       // its scene's name
  std::int64_t frame = 0;  // frames stepped (0 for a world's snapshot)
  std::int64_t steps = 0;  // the world's step count
  double time = 0.0;
  std::size_t bodies = 0;
};
[[nodiscard]] SnapshotInfo snapshot_info(std::span<const std::uint8_t> bytes,
                                         const std::string& source);

// Whether bytes start like a snapshot / an archive (their magic numbers).
[[nodiscard]] bool looks_like_snapshot(std::span<const std::uint8_t> bytes);
[[nodiscard]] bool looks_like_archive(std::span<const std::uint8_t> bytes);

// --- snapshot files ---
// Written as an output::AtomicFile (a temporary beside `path`, renamed over
// it once complete: never left half written). Throws InputError when the
// policy refuses the path, RunError when the write fails.
void save_snapshot(const Simulation& simulation, const std::string& path);
void save_snapshot(const World& world, const std::string& path);
// Throws InputError naming the file for one that can't be read or is not a
// valid snapshot.
[[nodiscard]] Simulation load_simulation(const std::string& path);
[[nodiscard]] World load_world(const std::string& path);
// The whole file (InputError naming it when it can't be read or is larger
// than `max_bytes`, checked against its length before anything is read).
[[nodiscard]] Bytes read_file_bytes(const std::string& path,
                                    std::uint64_t max_bytes = max_snapshot_bytes);

// --- archives: snapshots appended to one file ---
//
// Each snapshot is a record with its own length and CRC-32, written to the
// operating system as it is appended, so a run killed at any moment (even by
// SIGKILL) leaves an archive readable up to its last complete record. close()
// appends an index of the records; without one (a killed run), the reader
// rebuilds it by reading the records' headers only.
//
// A writer goes through the output policy (apps/README.md, "Output files"):
// it holds an exclusive lock on the file while it lives (a second writer is
// refused), creates a new archive or appends to an existing one after its
// last complete snapshot, and refuses a file that is not an archive. Nothing
// is written before the first append(). abandon() puts the file back as it
// was (an archive it created is removed).
class ArchiveWriter {
 public:
  // Opens (or creates) the archive and reads its records; throws InputError
  // when the policy refuses the path, the file is not an archive, or another
  // writer holds it.
  explicit ArchiveWriter(const std::string& path);
  ~ArchiveWriter();  // close(), errors ignored (unless abandoned)
  ArchiveWriter(const ArchiveWriter&) = delete;
  ArchiveWriter& operator=(const ArchiveWriter&) = delete;

  // Appends a snapshot of the simulation at its current frame. Throws
  // RunError when the write fails.
  void append(const Simulation& simulation);
  // Writes the index, flushes to disk and closes the file (once; later calls
  // do nothing).
  void close();
  // Puts the file back as it was when opened (never throws).
  void abandon() noexcept;
  // The snapshots in the archive (those it held before, and those appended).
  [[nodiscard]] std::size_t size() const { return index_.size(); }
  // The frame of the archive's last snapshot, if it has one.
  [[nodiscard]] std::optional<std::int64_t> last_frame() const;

 private:
  void write(const Bytes& bytes);
  std::string path_;
  std::unique_ptr<output::AppendFile> file_;
  std::uint64_t offset_ = 0;  // where the next record goes
  struct Entry {
    std::int64_t frame;
    std::uint64_t offset;
  };
  std::vector<Entry> index_;
  bool started_ = false;  // something was written
  bool closed_ = false;
};

class ArchiveReader {
 public:
  // Reads the index (or rebuilds it from the records' headers). Throws
  // InputError naming the file when it is not an archive or can't be read.
  explicit ArchiveReader(const std::string& path);

  // The number of complete snapshots, and the frame of each (in order).
  [[nodiscard]] std::size_t size() const { return records_.size(); }
  [[nodiscard]] std::int64_t frame(std::size_t i) const;
  [[nodiscard]] std::vector<std::int64_t> frames() const;
  // Whether the file ends with its index (false: a run that was killed).
  [[nodiscard]] bool complete() const { return complete_; }
  // The position of the snapshot of this frame, if there is one.
  [[nodiscard]] std::optional<std::size_t> find(std::int64_t frame) const;
  // The i-th snapshot's bytes, read alone and checked; throws InputError
  // naming the file and the record for i out of range or a bad checksum.
  [[nodiscard]] Bytes snapshot(std::size_t i) const;
  [[nodiscard]] Simulation simulation(std::size_t i) const;

 private:
  friend class ArchiveWriter;
  struct Record {
    std::int64_t frame;
    std::uint64_t offset;  // of the record's header
    std::uint64_t length;  // of its snapshot
  };
  bool read_index(std::ifstream& in, std::uint64_t size);
  void scan(std::ifstream& in, std::uint64_t size);
  std::string path_;
  std::vector<Record> records_;
  std::uint64_t records_end_ = 0;  // just after the last complete record
  bool complete_ = false;
};

// CRC-32 (ISO-HDLC, as zlib's crc32 and Python's zlib.crc32 compute it).
[[nodiscard]] std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

}  // namespace calder
