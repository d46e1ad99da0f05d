// SPDX-License-Identifier: MIT
// calder: the byte level of snapshots and archives (docs/SNAPSHOTS.md):
// little-endian numbers written byte by byte (the same file on any host),
// checked reads that throw InputError naming the file and the section, and
// the sections of a snapshot with their CRC-32s.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "calder/error.hpp"
#include "calder/snapshot.hpp"

namespace calder::snapshot_detail {

inline constexpr char kSnapshotMagic[8] = {'C', 'A', 'L', 'D', 'S', 'N', 'A', 'P'};
inline constexpr char kArchiveMagic[8] = {'C', 'A', 'L', 'D', 'A', 'R', 'C', 'H'};
inline constexpr char kArchiveEnd[8] = {'C', 'A', 'L', 'D', 'A', 'E', 'N', 'D'};
inline constexpr std::size_t kHeaderBytes = 16;   // magic, version, section count
inline constexpr std::size_t kSectionBytes = 16;  // tag, CRC-32, length
inline constexpr std::uint32_t kMaxSections = 16;

// Bytes up to the next multiple of 8.
inline std::uint64_t padded(std::uint64_t n) { return (n + 7U) & ~std::uint64_t{7}; }

class Out {
 public:
  void u8(std::uint8_t v) { bytes.push_back(v); }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void i64(std::int64_t v) { u64(static_cast<std::uint64_t>(v)); }
  void f64(double v) {
    std::uint64_t u = 0;
    std::memcpy(&u, &v, sizeof u);
    u64(u);
  }
  // Many doubles at once (a body column): one resize, then the bytes.
  void f64s(std::span<const double> values) {
    std::size_t at = bytes.size();
    bytes.resize(at + 8 * values.size());
    for (const double v : values) {
      std::uint64_t u = 0;
      std::memcpy(&u, &v, sizeof u);
      for (int i = 0; i < 8; ++i) bytes[at++] = static_cast<std::uint8_t>(u >> (8 * i));
    }
  }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    bytes.insert(bytes.end(), s.begin(), s.end());
  }
  // A name of at most 15 bytes in 16, NUL-padded.
  void name16(const std::string& s) {
    for (std::size_t i = 0; i < 16; ++i) {
      u8(i < s.size() && i < 15 ? static_cast<std::uint8_t>(s[i]) : std::uint8_t{0});
    }
  }
  void raw(std::span<const std::uint8_t> b) { bytes.insert(bytes.end(), b.begin(), b.end()); }
  void pad8() { bytes.resize(static_cast<std::size_t>(padded(bytes.size())), 0); }
  Bytes bytes;
};

class In {
 public:
  In(std::span<const std::uint8_t> bytes, std::string where)
      : bytes_(bytes), where_(std::move(where)) {}

  [[noreturn]] void fail(const std::string& what) const { throw InputError(where_ + ": " + what); }
  [[nodiscard]] std::size_t left() const { return bytes_.size() - at_; }
  [[nodiscard]] std::size_t position() const { return at_; }

  void skip(std::size_t n) { (void)take(n); }
  std::uint8_t u8() { return take(1)[0]; }
  std::uint32_t u32() {
    const std::uint8_t* p = take(4);
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8U) | p[i];
    return v;
  }
  std::uint64_t u64() {
    const std::uint8_t* p = take(8);
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8U) | p[i];
    return v;
  }
  std::int64_t i64() { return static_cast<std::int64_t>(u64()); }
  double f64() {
    const std::uint64_t u = u64();
    double v = 0.0;
    std::memcpy(&v, &u, sizeof v);
    return v;
  }
  // values.size() doubles at once (a body column).
  void f64s(std::span<double> values) {
    const std::uint8_t* p = take(8 * values.size());
    for (double& v : values) {
      std::uint64_t u = 0;
      for (int i = 7; i >= 0; --i) u = (u << 8U) | p[i];
      std::memcpy(&v, &u, sizeof v);
      p += 8;
    }
  }
  bool boolean() {
    const std::uint8_t v = u8();
    if (v > 1) fail("a flag of value " + std::to_string(v) + " (0 or 1)");
    return v == 1;
  }
  std::string str() {
    const std::uint32_t n = u32();
    if (n > left()) fail("a text of " + std::to_string(n) + " bytes runs past the section's end");
    const std::uint8_t* p = take(n);
    return {reinterpret_cast<const char*>(p), n};
  }
  std::string name16() {
    const std::uint8_t* p = take(16);
    std::size_t n = 0;
    while (n < 16 && p[n] != 0) ++n;
    return {reinterpret_cast<const char*>(p), n};
  }
  // A u32 count of items of at least min_item_bytes each, checked against
  // the bytes left (a corrupted count can't allocate gigabytes).
  std::size_t count(std::size_t min_item_bytes) {
    const std::uint32_t n = u32();
    if (static_cast<std::uint64_t>(n) * min_item_bytes > left()) {
      fail("a count of " + std::to_string(n) + " runs past the section's end");
    }
    return n;
  }
  // Every byte read.
  void finish() const {
    if (left() != 0) fail(std::to_string(left()) + " bytes left over at its end");
  }

 private:
  const std::uint8_t* take(std::size_t n) {
    if (n > left()) {
      fail("ends early: " + std::to_string(n) + " more bytes needed at byte " +
           std::to_string(at_) + " of " + std::to_string(bytes_.size()));
    }
    const std::uint8_t* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  std::span<const std::uint8_t> bytes_;
  std::string where_;
  std::size_t at_ = 0;
};

// Collects sections, then writes the snapshot: header, then each section as
// tag, CRC-32 of its payload, payload length, payload, zeros to 8 bytes.
class SectionWriter {
 public:
  void add(const char (&tag)[5], Bytes payload) { sections_.emplace_back(tag, std::move(payload)); }
  // The format version the header says (1 unless a section needs more).
  void require_version(std::uint32_t version) { version_ = std::max(version_, version); }
  Bytes finish() const {
    Out out;
    std::size_t total = kHeaderBytes;
    for (const auto& section : sections_) {
      total += kSectionBytes + static_cast<std::size_t>(padded(section.second.size()));
    }
    out.bytes.reserve(total);
    for (const char c : kSnapshotMagic) out.u8(static_cast<std::uint8_t>(c));
    out.u32(version_);
    out.u32(static_cast<std::uint32_t>(sections_.size()));
    for (const auto& [tag, payload] : sections_) {
      for (std::size_t i = 0; i < 4; ++i) out.u8(static_cast<std::uint8_t>(tag[i]));
      out.u32(crc32(payload));
      out.u64(payload.size());
      out.raw(payload);
      out.pad8();
    }
    return std::move(out.bytes);
  }

 private:
  std::vector<std::pair<std::string, Bytes>> sections_;
  std::uint32_t version_ = 1;
};

// A snapshot's sections, each checked against its CRC-32. Throws InputError
// naming `source` for anything wrong with the framing.
class Sections {
 public:
  Sections(std::span<const std::uint8_t> bytes, const std::string& source);
  [[nodiscard]] bool has(const std::string& tag) const { return sections_.count(tag) != 0; }
  // The section's reader (InputError when the snapshot lacks it).
  [[nodiscard]] In open(const std::string& tag) const;

 private:
  std::string source_;
  std::map<std::string, std::span<const std::uint8_t>> sections_;
};

}  // namespace calder::snapshot_detail
