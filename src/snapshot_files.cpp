// SPDX-License-Identifier: MIT
// calder: a snapshot's framing (sections and checksums), snapshot files and
// archives (see calder/snapshot.hpp and docs/SNAPSHOTS.md).
#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <ios>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "calder/error.hpp"
#include "calder/snapshot.hpp"
#include "output/output.hpp"
#include "snapshot_bytes.hpp"

namespace calder {

namespace {

using snapshot_detail::In;
using snapshot_detail::kArchiveEnd;
using snapshot_detail::kArchiveMagic;
using snapshot_detail::kHeaderBytes;
using snapshot_detail::kSectionBytes;
using snapshot_detail::kSnapshotMagic;
using snapshot_detail::Out;
using snapshot_detail::padded;

// CRC-32 by slicing-by-8 (Kounavis and Berry, "A Systematic Approach to
// Building High Performance Software-Based CRC Generators", 2005): table k
// gives the CRC of a byte followed by k zero bytes, so that eight bytes are
// folded per step instead of one.
using CrcTables = std::array<std::array<std::uint32_t, 256>, 8>;
constexpr CrcTables crc_tables() {
  CrcTables t{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1U) != 0 ? 0xEDB88320U ^ (c >> 1U) : c >> 1U;
    t[0][n] = c;
  }
  for (std::size_t k = 1; k < 8; ++k) {
    for (std::size_t n = 0; n < 256; ++n) t[k][n] = (t[k - 1][n] >> 8U) ^ t[0][t[k - 1][n] & 0xFFU];
  }
  return t;
}
constexpr CrcTables kCrc = crc_tables();

std::uint32_t load32(const std::uint8_t* p) {
  return p[0] | (std::uint32_t{p[1]} << 8U) | (std::uint32_t{p[2]} << 16U) |
         (std::uint32_t{p[3]} << 24U);
}

bool starts_with(std::span<const std::uint8_t> bytes, const char (&magic)[8]) {
  return bytes.size() >= 8 && std::memcmp(bytes.data(), magic, 8) == 0;
}

std::string named(const std::string& source) { return detail::printable(source, 240); }

// A section tag as a message shows it.
std::string tag_text(const std::uint8_t* p) {
  return detail::printable(std::string(reinterpret_cast<const char*>(p), 4));
}

bool known_tag(const std::string& tag) {
  for (const char* t : {"SCEN", "SIMU", "WRLD", "RAND", "FLDS", "BODY", "ADPT"}) {
    if (tag == t) return true;
  }
  return false;
}

// The archive's record header: tag, CRC-32 of the payload, frame, length.
constexpr std::size_t kRecordBytes = 24;

std::string errno_text() { return std::strerror(errno); }

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  crc = ~crc;
  const std::uint8_t* p = bytes.data();
  std::size_t n = bytes.size();
  for (; n >= 8; n -= 8, p += 8) {
    const std::uint32_t lo = crc ^ load32(p);
    const std::uint32_t hi = load32(p + 4);
    crc = kCrc[7][lo & 0xFFU] ^ kCrc[6][(lo >> 8U) & 0xFFU] ^ kCrc[5][(lo >> 16U) & 0xFFU] ^
          kCrc[4][lo >> 24U] ^ kCrc[3][hi & 0xFFU] ^ kCrc[2][(hi >> 8U) & 0xFFU] ^
          kCrc[1][(hi >> 16U) & 0xFFU] ^ kCrc[0][hi >> 24U];
  }
  for (; n > 0; --n, ++p) crc = kCrc[0][(crc ^ *p) & 0xFFU] ^ (crc >> 8U);
  return ~crc;
}

bool looks_like_snapshot(std::span<const std::uint8_t> bytes) {
  return starts_with(bytes, kSnapshotMagic);
}

bool looks_like_archive(std::span<const std::uint8_t> bytes) {
  return starts_with(bytes, kArchiveMagic);
}

namespace snapshot_detail {

Sections::Sections(std::span<const std::uint8_t> bytes, const std::string& source)
    : source_(named(source)) {
  In in(bytes, source_);
  if (looks_like_archive(bytes)) {
    in.fail("an archive of snapshots, not one snapshot (read a frame of it with ArchiveReader)");
  }
  if (!looks_like_snapshot(bytes)) in.fail("not a calder snapshot (no CALDSNAP at its start)");
  if (bytes.size() < kHeaderBytes) in.fail("truncated in its header");
  for (int i = 0; i < 8; ++i) (void)in.u8();
  const std::uint32_t version = in.u32();
  if (version < 1 || version > kSnapshotVersion) {
    in.fail("snapshot format version " + std::to_string(version) +
            "; this calder reads versions 1 to " + std::to_string(kSnapshotVersion));
  }
  const std::uint32_t count = in.u32();
  if (count > kMaxSections) in.fail("corrupted header: " + std::to_string(count) + " sections");
  for (std::uint32_t s = 0; s < count; ++s) {
    const std::string which = "section " + std::to_string(s + 1) + " of " + std::to_string(count);
    if (in.left() < kSectionBytes) in.fail("truncated: " + which + " is missing");
    const std::size_t at = in.position();
    const std::string tag = tag_text(bytes.data() + at);
    for (int i = 0; i < 4; ++i) (void)in.u8();
    const std::uint32_t crc = in.u32();
    const std::uint64_t length = in.u64();
    if (!known_tag(tag)) in.fail(which + " has the unknown tag '" + tag + "' (corrupted?)");
    if (length > in.left() || padded(length) > in.left()) {
      in.fail("truncated: section " + tag + " needs " + std::to_string(padded(length)) +
              " bytes, " + std::to_string(in.left()) + " are left");
    }
    const auto payload = bytes.subspan(in.position(), static_cast<std::size_t>(length));
    if (crc32(payload) != crc) in.fail("section " + tag + ": checksum mismatch (corrupted)");
    if (!sections_.emplace(tag, payload).second) in.fail("section " + tag + " appears twice");
    in.skip(static_cast<std::size_t>(length));
    for (std::uint64_t i = length; i < padded(length); ++i) {
      if (in.u8() != 0) in.fail("non-zero padding after section " + tag + " (corrupted)");
    }
  }
  if (in.left() != 0) in.fail(std::to_string(in.left()) + " bytes after the last section");
}

In Sections::open(const std::string& tag) const {
  const auto it = sections_.find(tag);
  if (it == sections_.end()) {
    throw InputError(source_ + ": the section " + tag + " is missing");
  }
  return {it->second, source_ + ": section " + tag};
}

}  // namespace snapshot_detail

// --- snapshot files ---

Bytes read_file_bytes(const std::string& path, std::uint64_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(named(path) + ": can't open: " + errno_text());
  // The length first: nothing is allocated for a file larger than the limit,
  // and the buffer is allocated once.
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  in.seekg(0, std::ios::beg);
  if (end < 0 || !in) throw InputError(named(path) + ": can't read: not a regular file");
  const auto length = static_cast<std::uint64_t>(end);
  if (length > max_bytes) {
    throw InputError(named(path) + ": " + std::to_string(length) + " bytes, larger than the " +
                     std::to_string(max_bytes) + " bytes a snapshot may have (corrupted?)");
  }
  Bytes bytes(static_cast<std::size_t>(length));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(length));
  if (static_cast<std::uint64_t>(std::max<std::streamsize>(in.gcount(), 0)) != length) {
    throw InputError(named(path) + ": read failed (the file changed while it was read?)");
  }
  return bytes;
}

void save_snapshot(const Simulation& simulation, const std::string& path) {
  output::write_file("", path, to_snapshot(simulation));
}

void save_snapshot(const World& world, const std::string& path) {
  output::write_file("", path, to_snapshot(world));
}

Simulation load_simulation(const std::string& path) {
  return simulation_from_snapshot(read_file_bytes(path), path);
}

World load_world(const std::string& path) {
  return world_from_snapshot(read_file_bytes(path), path);
}

// --- archives ---

ArchiveWriter::ArchiveWriter(const std::string& path)
    : path_(path), file_(std::make_unique<output::AppendFile>("", path)) {
  offset_ = kHeaderBytes;
  if (file_->original_size() == 0) return;  // a new (or empty) file: header first
  const Bytes head = file_->read_at(0, kHeaderBytes);
  if (!looks_like_archive(head)) {
    throw InputError(named(path) +
                     ": not a calder archive (no CALDARCH at its start); "
                     "refusing to append to it");
  }
  // Its records, as a reader finds them (the index, or the headers' scan).
  const ArchiveReader existing(path);
  for (const ArchiveReader::Record& r : existing.records_) index_.push_back({r.frame, r.offset});
  offset_ = existing.records_end_;
}

ArchiveWriter::~ArchiveWriter() {
  try {
    close();
  } catch (const Error&) {  // NOLINT(bugprone-empty-catch): a destructor can't report it
  }
}

std::optional<std::int64_t> ArchiveWriter::last_frame() const {
  if (index_.empty()) return std::nullopt;
  return index_.back().frame;
}

void ArchiveWriter::write(const Bytes& bytes) {
  if (!started_) {
    started_ = true;
    if (file_->original_size() == 0) {
      Out header;
      for (const char c : kArchiveMagic) header.u8(static_cast<std::uint8_t>(c));
      header.u32(kArchiveVersion);
      header.u32(0);
      file_->append(header.bytes);
    } else {
      // The old index and trailer (or a torn last record) give way to the
      // new records; abandon() puts them back.
      file_->cut_to(offset_);
    }
  }
  file_->append(bytes);
  offset_ += bytes.size();
}

namespace {

// A record: "SNAP" or "INDX", the payload's CRC-32, the frame (-1 for the
// index), the payload's length, the payload, zeros to 8 bytes.
Bytes record(const char* tag, std::int64_t frame, const Bytes& payload) {
  Out out;
  for (int i = 0; i < 4; ++i) out.u8(static_cast<std::uint8_t>(tag[i]));
  out.u32(crc32(payload));
  out.i64(frame);
  out.u64(payload.size());
  out.raw(payload);
  out.pad8();
  return std::move(out.bytes);
}

}  // namespace

void ArchiveWriter::append(const Simulation& simulation) {
  if (closed_) throw RunError(named(path_) + ": the archive is closed");
  const std::uint64_t at = offset_;
  write(record("SNAP", simulation.frame(), to_snapshot(simulation)));
  index_.push_back({simulation.frame(), at});
}

void ArchiveWriter::close() {
  if (closed_) return;
  closed_ = true;
  if (!started_ && file_->original_size() != 0) {  // nothing appended: left as it was
    file_->keep();
    file_.reset();
    return;
  }
  Out index;
  index.u64(index_.size());
  for (const Entry& e : index_) {
    index.i64(e.frame);
    index.u64(e.offset);
  }
  const std::uint64_t at = offset_;
  Bytes tail = record("INDX", -1, index.bytes);
  Out end;
  end.u64(at);
  for (const char c : kArchiveEnd) end.u8(static_cast<std::uint8_t>(c));
  tail.insert(tail.end(), end.bytes.begin(), end.bytes.end());
  write(tail);
  file_->sync();
  file_->keep();
  file_.reset();
}

void ArchiveWriter::abandon() noexcept {
  if (closed_) return;
  closed_ = true;
  file_.reset();  // not kept: put back as it was
}

namespace {

// Reads n bytes at offset, or fewer at the end of the file.
Bytes read_at(std::ifstream& in, std::uint64_t offset, std::uint64_t n) {
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  Bytes bytes(static_cast<std::size_t>(n));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(n));
  bytes.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return bytes;
}

struct RecordHeader {
  std::string tag;
  std::uint32_t crc = 0;
  std::int64_t frame = 0;
  std::uint64_t length = 0;
};

// Whether a record's header can be one calder wrote: a snapshot no larger
// than max_snapshot_bytes, of a frame in 0..max_frames.
bool plausible(const RecordHeader& h) {
  return h.tag == "SNAP" && h.length <= max_snapshot_bytes && h.frame >= 0 && h.frame <= max_frames;
}

// The CRC-32 of n bytes at offset, read a MiB at a time (nullopt: the file
// ends first).
std::optional<std::uint32_t> crc_at(std::ifstream& in, std::uint64_t offset, std::uint64_t n) {
  constexpr std::uint64_t kChunk = std::uint64_t{1} << 20;
  std::uint32_t crc = 0;
  for (std::uint64_t done = 0; done < n;) {
    const Bytes part = read_at(in, offset + done, std::min(kChunk, n - done));
    if (part.empty()) return std::nullopt;
    crc = crc32(part, crc);
    done += part.size();
  }
  return crc;
}

RecordHeader parse_record(const Bytes& bytes, const std::string& where) {
  In in(bytes, where);
  RecordHeader h;
  h.tag = tag_text(bytes.data());
  (void)in.u32();
  h.crc = in.u32();
  h.frame = in.i64();
  h.length = in.u64();
  return h;
}

}  // namespace

ArchiveReader::ArchiveReader(const std::string& path) : path_(path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(named(path) + ": can't open: " + errno_text());
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(std::max<std::streamoff>(in.tellg(), 0));
  const Bytes header = read_at(in, 0, kHeaderBytes);
  if (!looks_like_archive(header)) {
    throw InputError(named(path) + ": not a calder archive (no CALDARCH at its start)");
  }
  if (header.size() < kHeaderBytes) throw InputError(named(path) + ": truncated in its header");
  In h(header, named(path));
  for (int i = 0; i < 8; ++i) (void)h.u8();
  if (const std::uint32_t version = h.u32(); version != kArchiveVersion) {
    throw InputError(named(path) + ": archive format version " + std::to_string(version) +
                     "; this calder reads version " + std::to_string(kArchiveVersion));
  }
  complete_ = read_index(in, size);
  if (!complete_) scan(in, size);
}

bool ArchiveReader::read_index(std::ifstream& in, std::uint64_t size) {
  if (size < kHeaderBytes + kRecordBytes + 16) return false;
  const Bytes end = read_at(in, size - 16, 16);
  if (end.size() != 16 || std::memcmp(end.data() + 8, kArchiveEnd, 8) != 0) return false;
  const std::uint64_t at = In(end, path_).u64();
  if (at < kHeaderBytes || at > size - 16 - kRecordBytes) return false;
  const RecordHeader h = parse_record(read_at(in, at, kRecordBytes), path_);
  if (h.tag != "INDX" || padded(h.length) != size - 16 - at - kRecordBytes) return false;
  // No more entries than records fit before it: nothing larger is allocated.
  if (h.length > 8 + 16 * (at / kRecordBytes)) return false;
  const Bytes payload = read_at(in, at + kRecordBytes, h.length);
  if (payload.size() != h.length || crc32(payload) != h.crc) return false;
  In index(payload, named(path_) + ": index");
  const std::uint64_t n = index.u64();
  if (n > h.length / 16) return false;
  std::vector<Record> records;
  for (std::uint64_t i = 0; i < n; ++i) {
    const std::int64_t frame = index.i64();
    const std::uint64_t offset = index.u64();
    if (offset < kHeaderBytes || offset + kRecordBytes > at) return false;
    const RecordHeader r = parse_record(read_at(in, offset, kRecordBytes), path_);
    if (!plausible(r) || r.frame != frame || offset + kRecordBytes + r.length > at) return false;
    records.push_back({frame, offset, r.length});
  }
  records_ = std::move(records);
  records_end_ = at;
  return true;
}

void ArchiveReader::scan(std::ifstream& in, std::uint64_t size) {
  records_.clear();
  std::uint64_t at = kHeaderBytes;
  std::optional<std::uint32_t> last_crc;
  while (size - at >= kRecordBytes) {
    const RecordHeader h = parse_record(read_at(in, at, kRecordBytes), path_);
    if (!plausible(h) || h.length > size - at - kRecordBytes) break;
    records_.push_back({h.frame, at, h.length});
    last_crc = h.crc;
    at += kRecordBytes + padded(h.length);
    if (at > size) break;
  }
  // A run killed while writing can leave a last record whose length made it
  // to the disk before all its bytes: keep it only when its checksum holds.
  if (!records_.empty()) {
    const Record& last = records_.back();
    if (crc_at(in, last.offset + kRecordBytes, last.length) != last_crc) records_.pop_back();
  }
  records_end_ = records_.empty()
                     ? kHeaderBytes
                     : records_.back().offset + kRecordBytes + padded(records_.back().length);
}

std::int64_t ArchiveReader::frame(std::size_t i) const {
  if (i >= records_.size()) {
    throw InputError(named(path_) + ": no snapshot " + std::to_string(i) + " (the archive has " +
                     std::to_string(records_.size()) + ")");
  }
  return records_[i].frame;
}

std::vector<std::int64_t> ArchiveReader::frames() const {
  std::vector<std::int64_t> out;
  out.reserve(records_.size());
  for (const Record& r : records_) out.push_back(r.frame);
  return out;
}

std::optional<std::size_t> ArchiveReader::find(std::int64_t frame) const {
  for (std::size_t i = records_.size(); i-- > 0;) {
    if (records_[i].frame == frame) return i;
  }
  return std::nullopt;
}

Bytes ArchiveReader::snapshot(std::size_t i) const {
  (void)frame(i);  // the range check
  const Record& r = records_[i];
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw InputError(named(path_) + ": can't open: " + errno_text());
  const Bytes header = read_at(in, r.offset, kRecordBytes);
  const std::string where = named(path_) + ": snapshot of frame " + std::to_string(r.frame);
  if (header.size() != kRecordBytes) throw InputError(where + ": truncated");
  const RecordHeader h = parse_record(header, where);
  Bytes payload = read_at(in, r.offset + kRecordBytes, r.length);
  if (payload.size() != r.length) throw InputError(where + ": truncated");
  if (crc32(payload) != h.crc) throw InputError(where + ": checksum mismatch (corrupted)");
  return payload;
}

Simulation ArchiveReader::simulation(std::size_t i) const {
  return simulation_from_snapshot(snapshot(i), path_ + " (frame " + std::to_string(frame(i)) + ")");
}

}  // namespace calder
