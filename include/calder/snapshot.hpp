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
// The format (docs/SNAPSHOTS.md) is little-endian on every platform, has a
// version and a CRC-32 per section, and is read without calder by a few lines
// of numpy (python/calder/snapshot_reader.py). A file that is truncated,
// corrupted, of another version or not a snapshot is refused with an
// InputError whose one line names the file and what is wrong.
//
// A world holding C++ code (a CustomForce field, an AttractionLaw with a
// custom function) can't be saved: save throws calder::Error naming the field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "calder/scene.hpp"
#include "calder/world.hpp"

namespace calder {

// The newest format version; every version from 1 to it is read. A snapshot
// is written as version 1 unless it holds an adaptive integrator's state
// (section ADPT, version 2), so that what version 1 could hold stays
// readable by a calder that reads only version 1.
inline constexpr std::uint32_t kSnapshotVersion = 2;
// The archive format's version (the snapshots inside carry their own).
inline constexpr std::uint32_t kArchiveVersion = 1;

using Bytes = std::vector<std::uint8_t>;

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
// Written to a temporary file beside `path`, renamed over it once complete:
// never left half written. Throws RunError when the write fails.
void save_snapshot(const Simulation& simulation, const std::string& path);
void save_snapshot(const World& world, const std::string& path);
// Throws InputError naming the file for one that can't be read or is not a
// valid snapshot.
[[nodiscard]] Simulation load_simulation(const std::string& path);
[[nodiscard]] World load_world(const std::string& path);
// The whole file (InputError naming it when it can't be read).
[[nodiscard]] Bytes read_file_bytes(const std::string& path);

// --- archives: snapshots appended to one file ---
//
// Each snapshot is a record with its own length and CRC-32, flushed as it is
// written, so a run killed at any moment (even by SIGKILL) leaves an archive
// readable up to its last complete record. close() appends an index of the
// records; without one (a killed run), the reader rebuilds it by reading the
// records' headers only.
class ArchiveWriter {
 public:
  // Creates (or truncates) the file; throws RunError when it can't.
  explicit ArchiveWriter(const std::string& path);
  ~ArchiveWriter();  // close(), errors ignored
  ArchiveWriter(const ArchiveWriter&) = delete;
  ArchiveWriter& operator=(const ArchiveWriter&) = delete;

  // Appends a snapshot of the simulation at its current frame and flushes
  // it to the operating system. Throws RunError when the write fails.
  void append(const Simulation& simulation);
  // Writes the index and closes the file (once; later calls do nothing).
  void close();
  [[nodiscard]] std::size_t size() const { return index_.size(); }

 private:
  void write(const Bytes& bytes);
  std::string path_;
  std::ofstream out_;
  std::uint64_t offset_ = 0;
  struct Entry {
    std::int64_t frame;
    std::uint64_t offset;
  };
  std::vector<Entry> index_;
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
  struct Record {
    std::int64_t frame;
    std::uint64_t offset;  // of the record's header
    std::uint64_t length;  // of its snapshot
  };
  bool read_index(std::ifstream& in, std::uint64_t size);
  void scan(std::ifstream& in, std::uint64_t size);
  std::string path_;
  std::vector<Record> records_;
  bool complete_ = false;
};

// CRC-32 (ISO-HDLC, as zlib's crc32 and Python's zlib.crc32 compute it).
[[nodiscard]] std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

}  // namespace calder
