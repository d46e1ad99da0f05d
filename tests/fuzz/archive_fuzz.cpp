// SPDX-License-Identifier: MIT
// libFuzzer target: the archive reader (calder run FILE.archive, calder.Archive)
// and the archive appender on whatever file it is given (calder run --archive
// FILE over an existing file). Bad input must end in InputError, never a
// crash, a hang or a huge allocation; an appender that accepted the file must
// leave an archive that reads back with its snapshot last, and one that gave
// up must leave the file byte for byte as it was.
#include <unistd.h>

#include <calder/error.hpp>
#include <calder/scene.hpp>
#include <calder/snapshot.hpp>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

std::string scratch_path() {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir != nullptr ? dir : "/tmp") + "/calder-fuzz-archive-" +
         std::to_string(::getpid()) + ".archive";
}

void put(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

std::vector<std::uint8_t> get(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void read_archive(const std::string& path) {
  try {
    const calder::ArchiveReader archive(path);
    for (std::size_t i = 0; i < archive.size() && i < 4; ++i) {
      try {
        calder::Simulation simulation = archive.simulation(i);
        if (simulation.world().body_count() <= 1000) simulation.step();
      } catch (const calder::Error&) {
      }
    }
  } catch (const calder::Error&) {
  }
}

void append_to(const std::string& path, const std::vector<std::uint8_t>& before) {
  static const calder::Simulation small(calder::builtin_scene("example-2.1"));
  try {
    calder::ArchiveWriter writer(path);
    writer.append(small);
    writer.close();
  } catch (const calder::InputError&) {
    if (get(path) != before) std::abort();  // refused, yet changed
    return;
  }
  const calder::ArchiveReader archive(path);
  if (archive.size() == 0 || archive.frame(archive.size() - 1) != small.frame()) std::abort();
  (void)archive.simulation(archive.size() - 1);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = scratch_path();
  put(path, data, size);
  read_archive(path);
  append_to(path, std::vector<std::uint8_t>(data, data + size));
  ::unlink(path.c_str());
  return 0;
}
