// SPDX-License-Identifier: MIT
// The output module (src/output/output.hpp): an atomic file appears whole or not
// at all, and its temporary is in the registry the signal handler empties; an
// appended file is put back byte for byte; the outputs of a run are checked
// against its inputs and one another before anything is created.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <calder/error.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <string>
#include <vector>
#include "../src/output/output.hpp"

#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
namespace output = calder::output;

struct Folder {
  fs::path dir;
  Folder() {
    std::string pattern = (fs::temp_directory_path() / "calder-output-XXXXXX").string();
    dir = ::mkdtemp(pattern.data());
  }
  ~Folder() { fs::remove_all(dir); }
  [[nodiscard]] std::string file(const std::string& name) const { return (dir / name).string(); }
  [[nodiscard]] std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
};

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(OutputAtomicFile, AppearsWholeOnCommitAndNotAtAllWithout) {
  const Folder folder;
  const std::string path = folder.file("out.bin");
  put(path, "old");
  {
    output::AtomicFile file("test", path);
    file.write_all("new", 3);
    EXPECT_EQ(read_all(path), "old");
    EXPECT_EQ(folder.entries().size(), 2U);  // the target and the temporary beside it
    file.commit();
  }
  EXPECT_EQ(read_all(path), "new");
  {
    output::AtomicFile file("test", path);
    file.write_all("partial", 7);
  }
  EXPECT_EQ(read_all(path), "new");
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"out.bin"});
}

TEST(OutputAtomicFile, ItsTemporaryIsRegisteredForTheSignalHandler) {
  const Folder folder;
  output::AtomicFile file("test", folder.file("out.bin"));
  file.write_all("partial", 7);
  ASSERT_TRUE(fs::exists(file.temp_path()));
  {
    // What the watchdog does when a job doesn't stop after a signal.
    const std::lock_guard<std::mutex> lock(output::temporaries_lock());
    output::remove_temporaries_locked();
  }
  EXPECT_TRUE(folder.entries().empty());
}

TEST(OutputAtomicFile, ThePolicyRefusesBeforeCreatingAnything) {
  const Folder folder;
  const std::string ro = folder.file("ro.bin");
  put(ro, "old");
  ::chmod(ro.c_str(), 0444);
  calder::test::expect_error([&] { output::AtomicFile f("test", ro); }, {"write-protected"});
  ::symlink(folder.file("missing").c_str(), folder.file("dangling").c_str());
  calder::test::expect_error([&] { output::AtomicFile f("test", folder.file("dangling")); },
                             {"symbolic link to a missing file"});
  calder::test::expect_error([&] { output::AtomicFile f("test", folder.file("no/out.bin")); },
                             {"does not exist"});
  EXPECT_EQ(folder.entries(), (std::vector<std::string>{"dangling", "ro.bin"}));
  EXPECT_EQ(read_all(ro), "old");
}

TEST(OutputCheck, AnOutputIsNeitherAnInputNorAnotherOutput) {
  const Folder folder;
  const std::string scene = folder.file("mine.toml");
  put(scene, "name = 'x'");
  ::symlink(scene.c_str(), folder.file("alias").c_str());
  const std::vector<output::NamedPath> inputs = {{"the scene file", scene}};
  calder::test::expect_error(
      [&] {
        output::check_outputs(inputs, {{"--save", folder.file("alias")}});
      },
      {"--save", "the scene file", "refusing to overwrite it"});
  calder::test::expect_error(
      [&] {
        output::check_outputs({}, {{"--trajectory", folder.file("t")},
                                   {"--archive", folder.file("./t"), output::Kind::archive}});
      },
      {"is also", "--trajectory"});
  calder::test::expect_error(
      [&] {
        output::check_outputs({}, {{"--png", folder.dir.string(), output::Kind::folder},
                                   {"--gif", folder.file("a.gif")}});
      },
      {"is inside --png"});
  calder::test::expect_error(
      [&] {
        output::check_outputs({}, {{"--archive", "/dev/null", output::Kind::archive}});
      },
      {"regular file"});
  output::check_outputs(inputs, {{"--save", folder.file("run.snap")}, {"--trajectory", "-"}});
  EXPECT_EQ(folder.entries(), (std::vector<std::string>{"alias", "mine.toml"}));
}

TEST(OutputAppendFile, PutBackByteForByteUnlessKept) {
  const Folder folder;
  const std::string path = folder.file("log");
  put(path, "0123456789");
  {
    output::AppendFile file("test", path);
    EXPECT_EQ(file.original_size(), 10U);
    file.cut_to(6);
    const std::string more = "abcdef";
    file.append({reinterpret_cast<const std::uint8_t*>(more.data()), more.size()});
    EXPECT_EQ(read_all(path), "012345abcdef");
    calder::test::expect_error([&] { output::AppendFile again("test", path); }, {"locked"});
  }
  EXPECT_EQ(read_all(path), "0123456789");
  {
    output::AppendFile file("test", path);
    const std::string more = "!";
    file.append({reinterpret_cast<const std::uint8_t*>(more.data()), more.size()});
    file.keep();
  }
  EXPECT_EQ(read_all(path), "0123456789!");
  {
    const output::AppendFile created("test", folder.file("new"));
    EXPECT_TRUE(created.created());
  }
  EXPECT_FALSE(fs::exists(folder.file("new")));  // made, not kept: removed
}

}  // namespace
