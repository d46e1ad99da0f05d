// SPDX-License-Identifier: MIT
// Snapshots and archives: a run saved and loaded continues with the same bits
// as a run never stopped (every built-in scene, several seeds, the mouse
// held across the save); the format is the documented one; every truncation
// and every flipped byte is refused with one line naming the file.
#include <gtest/gtest.h>

#include <calder/calder.hpp>
#include <calder/snapshot.hpp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "support/test_support.hpp"

namespace {

using calder::Bytes;
using calder::Scene;
using calder::Simulation;

// Every bit of the bodies, the generators, the clock and the progress.
void expect_same_state(const Simulation& a, const Simulation& b, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(calder::state_hash(a.world()), calder::state_hash(b.world()));
  const calder::BodyView x = a.world().bodies();
  const calder::BodyView y = b.world().bodies();
  ASSERT_EQ(x.size(), y.size());
  calder::for_each_column(
      [&](const char* name, std::span<const double> p, std::span<const double> q) {
        EXPECT_EQ(std::memcmp(p.data(), q.data(), p.size_bytes()), 0) << name;
      },
      x, y);
  EXPECT_EQ(a.frame(), b.frame());
  EXPECT_EQ(a.world().time(), b.world().time());
  EXPECT_EQ(a.world().step_count(), b.world().step_count());
  const calder::Random& ra = a.world().random();
  const calder::Random& rb = b.world().random();
  EXPECT_EQ(ra.state(), rb.state());
  EXPECT_EQ(ra.spare_gaussian(), rb.spare_gaussian());
  // The next bytes saved are the same: fields, noise, mouse and scene too.
  EXPECT_EQ(calder::to_snapshot(a), calder::to_snapshot(b));
}

void step(Simulation& s, int frames) {
  for (int i = 0; i < frames; ++i) s.step();
}

// N frames, save, load, M more, against N + M straight.
void expect_round_trip(const Scene& scene, std::uint32_t seed, int n, int m,
                       const std::string& what) {
  Simulation straight(scene, seed);
  step(straight, n + m);
  Simulation first(scene, seed);
  step(first, n);
  const Bytes bytes = calder::to_snapshot(first);
  Simulation resumed = calder::simulation_from_snapshot(bytes, "memory");
  EXPECT_EQ(calder::to_snapshot(resumed), bytes) << what;  // a load keeps every byte
  step(resumed, m);
  expect_same_state(straight, resumed, what);
}

const std::uint32_t kSeeds[] = {0, 1, 42};

TEST(SnapshotRoundTrip, EveryBuiltinSceneAndSeedContinuesBitForBit) {
  for (const calder::SceneInfo& info : calder::builtin_scenes()) {
    for (const std::uint32_t seed : kSeeds) {
      expect_round_trip(calder::builtin_scene(info.name), seed, 37, 29,
                        info.name + " seed " + std::to_string(seed));
    }
  }
}

// The mouse pressed over the save, moving: on the first body (a toss grabs
// it) or on a draggable attractor, so that a held body, a drag, a reset or a
// wind while pressed is under way when the snapshot is taken.
Scene with_mouse_held(Scene scene, std::uint32_t seed) {
  Simulation probe(scene, seed);
  step(probe, 19);
  calder::Vec2 at = probe.world().body_count() > 0 ? probe.world().position(probe.world().body(0))
                                                   : calder::Vec2{100, 100};
  for (const calder::SceneField& f : scene.fields) {
    if (f.binding.draggable) at = std::get<calder::Attractor>(f.field).position;
  }
  scene.input.mouse_pressed = {{20, 50}, {60, 61}};
  scene.input.moves = {{20, at},
                       {30, at + calder::Vec2{5, 3}},
                       {37, at + calder::Vec2{9, -4}},
                       {40, at + calder::Vec2{12, 1}}};
  return scene;
}

TEST(SnapshotRoundTrip, MouseHeldAcrossTheSaveContinuesBitForBit) {
  bool tossed = false;
  bool dragged = false;
  for (const calder::SceneInfo& info : calder::builtin_scenes()) {
    for (const std::uint32_t seed : kSeeds) {
      const Scene scene = with_mouse_held(calder::builtin_scene(info.name), seed);
      Simulation at_save(scene, seed);
      step(at_save, 37);
      tossed = tossed || at_save.progress().tossed.has_value();
      dragged = dragged || !at_save.progress().grabs.empty();
      expect_round_trip(scene, seed, 37, 30,
                        info.name + " (mouse held) seed " + std::to_string(seed));
    }
  }
  EXPECT_TRUE(tossed) << "no scene was holding a body at the save";
  EXPECT_TRUE(dragged) << "no scene was dragging an attractor at the save";
}

TEST(SnapshotRoundTrip, SavedAtFrameZeroAndSavedTwice) {
  const Scene scene = calder::builtin_scene("example-2.5");
  expect_round_trip(scene, 3, 0, 40, "frame 0");
  // Saving, loading and saving again, five times over the run.
  Simulation straight(scene, 3);
  step(straight, 50);
  Simulation hop(scene, 3);
  for (int i = 0; i < 5; ++i) {
    step(hop, 10);
    hop = calder::simulation_from_snapshot(calder::to_snapshot(hop), "hop");
  }
  expect_same_state(straight, hop, "five hops");
}

TEST(SnapshotRoundTrip, AWorldWithPendingForcesAndAKeptGaussian) {
  calder::World world({.dt = 0.5, .integrator = calder::Integrator::velocity_verlet});
  world.add(calder::Gravity{});
  world.add(calder::NoiseWind{.strength = 0.3, .accumulate = true});
  world.add_body({.position = {10, 20}, .velocity = {1, -2}, .mass = 2.0, .radius = 3.0});
  world.add_body({.position = {50, 60}, .mass = 1.5, .friction = 0.3});
  world.step(3);
  world.apply_force(world.body(1), {0.25, -1.5});  // pending: in ax, ay
  (void)world.random().random_gaussian();          // keeps the pair's second value
  world.noise().noise_detail(3, 0.25);
  calder::World loaded = calder::world_from_snapshot(calder::to_snapshot(world), "world");
  EXPECT_EQ(loaded.acceleration(loaded.body(1)), world.acceleration(world.body(1)));
  EXPECT_EQ(loaded.random().random_gaussian(), world.random().random_gaussian());
  EXPECT_EQ(loaded.noise().noise(0.3, 0.7), world.noise().noise(0.3, 0.7));
  world.step(20);
  loaded.step(20);
  EXPECT_EQ(calder::state_hash(loaded), calder::state_hash(world));
  EXPECT_EQ(loaded.time(), world.time());
  EXPECT_EQ(calder::to_snapshot(loaded), calder::to_snapshot(world));
  // A world's snapshot is not a simulation's.
  calder::test::expect_error(
      [&] { (void)calder::simulation_from_snapshot(calder::to_snapshot(world), "w.snap"); },
      {"w.snap", "no scene"});
}

TEST(SnapshotRoundTrip, CodeCannotBeSaved) {
  calder::World world;
  world.add(
      calder::CustomForce{[](const calder::FieldContext&, std::size_t) { return calder::Vec2{}; }});
  calder::test::expect_error([&] { (void)calder::to_snapshot(world); },
                             {"field 0", "custom_force", "C++ code"});
}

// --- the format, read by hand as docs/SNAPSHOTS.md describes it ---

std::uint64_t le(const Bytes& b, std::size_t at, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8U) | b[at + static_cast<std::size_t>(i)];
  return v;
}

TEST(SnapshotFormat, TheDocumentedLayout) {
  EXPECT_EQ(calder::crc32(std::span<const std::uint8_t>(
                reinterpret_cast<const std::uint8_t*>("123456789"), 9)),
            0xCBF43926U);  // CRC-32's check value
  Simulation sim(calder::builtin_scene("example-2.5"), 5);
  step(sim, 12);
  const Bytes b = calder::to_snapshot(sim);
  ASSERT_EQ(std::string(b.begin(), b.begin() + 8), "CALDSNAP");
  EXPECT_EQ(le(b, 8, 4), 1U);  // version
  const std::uint64_t sections = le(b, 12, 4);
  std::size_t at = 16;
  std::vector<std::string> tags;
  for (std::uint64_t s = 0; s < sections; ++s) {
    const std::string tag(b.begin() + static_cast<std::ptrdiff_t>(at),
                          b.begin() + static_cast<std::ptrdiff_t>(at + 4));
    const std::uint64_t length = le(b, at + 8, 8);
    const std::size_t payload = at + 16;
    EXPECT_EQ(payload % 8, 0U);
    EXPECT_EQ(le(b, at + 4, 4),
              calder::crc32(std::span<const std::uint8_t>(b.data() + payload, length)));
    tags.push_back(tag);
    if (tag == "BODY") {
      const std::uint64_t n = le(b, payload, 8);
      const std::uint64_t columns = le(b, payload + 8, 4);
      ASSERT_EQ(n, sim.world().body_count());
      EXPECT_EQ(std::string(reinterpret_cast<const char*>(&b[payload + 16])), "x");
      EXPECT_EQ(std::string(reinterpret_cast<const char*>(&b[payload + 32])), "y");
      const std::size_t y_column = payload + 16 + 16 * columns + 8 * n;
      for (std::size_t i = 0; i < n; ++i) {
        double y = 0.0;
        const std::uint64_t bits = le(b, y_column + 8 * i, 8);
        std::memcpy(&y, &bits, 8);
        EXPECT_EQ(y, sim.world().bodies().y[i]);
      }
    }
    at = payload + ((length + 7) / 8) * 8;
  }
  EXPECT_EQ(at, b.size());
  EXPECT_EQ(tags, (std::vector<std::string>{"SCEN", "SIMU", "WRLD", "RAND", "FLDS", "BODY"}));
  const calder::SnapshotInfo info = calder::snapshot_info(b, "x");
  EXPECT_EQ(info.frame, 12);
  EXPECT_EQ(info.scene, "example-2.5");
  EXPECT_EQ(info.bodies, sim.world().body_count());
}

// One line naming the source, and an InputError.
void expect_refused(const Bytes& bytes, const std::string& what) {
  try {
    (void)calder::simulation_from_snapshot(bytes, "bad.snap");
    ADD_FAILURE() << what << ": accepted";
  } catch (const calder::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("bad.snap: ", 0), 0U) << what << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << what << ": " << message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": not an InputError: " << e.what();
  }
}

TEST(SnapshotFormat, EveryTruncationAndEveryFlippedByteIsRefused) {
  Simulation sim(calder::builtin_scene("exercise-2.7"), 1);
  step(sim, 5);
  const Bytes b = calder::to_snapshot(sim);
  for (std::size_t n = 0; n < b.size(); ++n) {
    expect_refused(Bytes(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(n)),
                   "cut at " + std::to_string(n));
  }
  for (std::size_t i = 0; i < b.size(); ++i) {
    Bytes flipped = b;
    flipped[i] ^= 0x10U;
    expect_refused(flipped, "byte " + std::to_string(i) + " flipped");
  }
  Bytes longer = b;
  longer.push_back(0);
  expect_refused(longer, "a byte more");
}

// --- files and archives ---

std::string temp_path(const std::string& name) { return testing::TempDir() + "calder_" + name; }

TEST(SnapshotFiles, SaveAndLoadAFile) {
  const std::string path = temp_path("file.snap");
  Simulation sim(calder::builtin_scene("exercise-2.16"), 42);
  step(sim, 10);
  calder::save_snapshot(sim, path);
  Simulation loaded = calder::load_simulation(path);
  step(sim, 10);
  step(loaded, 10);
  expect_same_state(sim, loaded, "file");
  calder::test::expect_error([] { (void)calder::load_simulation("/nonexistent/x.snap"); },
                             {"/nonexistent/x.snap", "can't open"});
  std::remove(path.c_str());
}

void write_bytes(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

TEST(SnapshotArchive, RandomAccessToEveryFrame) {
  const std::string path = temp_path("run.archive");
  const Scene scene = calder::builtin_scene("example-2.7");
  std::vector<Bytes> expected;
  {
    Simulation sim(scene, 1);
    calder::ArchiveWriter archive(path);
    for (int k = 0; k <= 6; ++k) {
      if (k > 0) step(sim, 5);
      archive.append(sim);
      expected.push_back(calder::to_snapshot(sim));
    }
  }
  const calder::ArchiveReader reader(path);
  EXPECT_TRUE(reader.complete());
  EXPECT_EQ(reader.frames(), (std::vector<std::int64_t>{0, 5, 10, 15, 20, 25, 30}));
  for (std::size_t i = 0; i < reader.size(); ++i) EXPECT_EQ(reader.snapshot(i), expected[i]);
  ASSERT_EQ(reader.find(15), std::optional<std::size_t>(3));
  EXPECT_FALSE(reader.find(16).has_value());
  Simulation straight(scene, 1);
  step(straight, 40);
  Simulation resumed = reader.simulation(3);
  step(resumed, 25);
  expect_same_state(straight, resumed, "archive frame 15");
  std::remove(path.c_str());
}

TEST(SnapshotArchive, ACutArchiveReadsUpToItsLastCompleteSnapshot) {
  const std::string path = temp_path("cut.archive");
  {
    Simulation sim(calder::builtin_scene("example-2.1"), 1);
    calder::ArchiveWriter archive(path);
    for (int k = 0; k < 4; ++k) {
      archive.append(sim);
      step(sim, 3);
    }
  }
  const Bytes whole = calder::read_file_bytes(path);
  // Record k starts at offsets[k]; the index follows the last.
  std::vector<std::size_t> offsets;
  for (std::size_t at = 16; whole[at] == 'S';) {
    offsets.push_back(at);
    at += 24 + ((le(whole, at + 16, 8) + 7) / 8) * 8;
    if (whole[at] != 'S') offsets.push_back(at);
  }
  ASSERT_EQ(offsets.size(), 5U);
  const std::string cut = temp_path("cut2.archive");
  for (std::size_t n = 16; n < whole.size(); n += 7) {
    write_bytes(cut, Bytes(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(n)));
    const calder::ArchiveReader reader(cut);
    std::size_t complete = 0;
    while (complete < 4 && offsets[complete + 1] <= n) ++complete;
    EXPECT_FALSE(reader.complete());
    ASSERT_EQ(reader.size(), complete) << "cut at " << n;
    for (std::size_t i = 0; i < complete; ++i) EXPECT_EQ(reader.frame(i), 3 * std::int64_t(i));
    if (complete > 0) (void)reader.simulation(complete - 1);
  }
  // A flipped byte in a snapshot: that one is refused, the others read.
  Bytes flipped = whole;
  flipped[offsets[1] + 100] ^= 1U;
  write_bytes(cut, flipped);
  const calder::ArchiveReader reader(cut);
  EXPECT_EQ(reader.size(), 4U);
  calder::test::expect_error([&] { (void)reader.snapshot(1); },
                             {"cut2.archive", "frame 3", "checksum"});
  (void)reader.simulation(2);
  calder::test::expect_error([&] { (void)calder::ArchiveReader(temp_path("none")); },
                             {"can't open"});
  write_bytes(cut, Bytes{'C', 'A', 'L', 'D', 'S', 'N', 'A', 'P'});
  calder::test::expect_error([&] { (void)calder::ArchiveReader{cut}; }, {"not a calder archive"});
  std::remove(path.c_str());
  std::remove(cut.c_str());
}

TEST(SnapshotArchive, AppendsAfterItsLastSnapshotAndAFailedRunLeavesItAsItWas) {
  const std::string path = temp_path("append.archive");
  std::remove(path.c_str());
  Simulation sim(calder::builtin_scene("example-2.1"), 1);
  {
    calder::ArchiveWriter archive(path);
    archive.append(sim);
    step(sim, 3);
    archive.append(sim);
  }
  const Bytes first = calder::read_file_bytes(path);
  {
    // Abandoned after appending (a run that failed): byte for byte as it was.
    calder::ArchiveWriter archive(path);
    EXPECT_EQ(archive.size(), 2U);
    EXPECT_EQ(archive.last_frame(), std::optional<std::int64_t>(3));
    step(sim, 3);
    archive.append(sim);
    archive.abandon();
  }
  EXPECT_EQ(calder::read_file_bytes(path), first);
  {
    calder::ArchiveWriter archive(path);
    // A second writer of the same file is refused while the first holds it.
    calder::test::expect_error([&] { calder::ArchiveWriter again(path); },
                               {"append.archive", "locked"});
    archive.append(sim);
  }
  const calder::ArchiveReader reader(path);
  EXPECT_TRUE(reader.complete());
  EXPECT_EQ(reader.frames(), (std::vector<std::int64_t>{0, 3, 6}));
  expect_same_state(sim, reader.simulation(2), "appended");
  // A torn last record (a killed run) gives way to the next run's.
  Bytes torn = calder::read_file_bytes(path);
  torn.resize(torn.size() - 100);
  write_bytes(path, torn);
  {
    calder::ArchiveWriter archive(path);
    EXPECT_EQ(archive.size(), 2U);
    step(sim, 3);
    archive.append(sim);
  }
  EXPECT_EQ(calder::ArchiveReader(path).frames(), (std::vector<std::int64_t>{0, 3, 9}));
  // A file that is not an archive is refused and left alone; a new archive
  // that a run abandons is removed.
  write_bytes(path, Bytes{'n', 'o', 't', 'e', 's'});
  calder::test::expect_error([&] { calder::ArchiveWriter w(path); }, {"not a calder archive"});
  EXPECT_EQ(calder::read_file_bytes(path), (Bytes{'n', 'o', 't', 'e', 's'}));
  std::remove(path.c_str());
  {
    calder::ArchiveWriter archive(path);
    archive.append(sim);
    archive.abandon();
  }
  EXPECT_FALSE(std::ifstream(path).good());
}

TEST(SnapshotLimits, CountersAndThreadsAreCheckedAsAScenesAre) {
  Simulation sim(calder::builtin_scene("example-2.9"), 1);
  calder::SimulationProgress progress = sim.progress();
  progress.frame = std::numeric_limits<std::int64_t>::max() - 1;
  calder::test::expect_error([&] { sim.restore_progress(progress); }, {"frame must be between"});
  calder::Scene scene = calder::builtin_scene("example-2.9");
  scene.world.threads = 100000;
  calder::test::expect_error([&] { scene.validate(); }, {"threads must be between 0 and 1024"});
  // A scene file's text is UTF-8; a snapshot's scene is held to the same.
  scene = calder::builtin_scene("example-2.9");
  scene.description = "a\xA0hundred";
  calder::test::expect_error([&] { scene.validate(); }, {"description is not valid UTF-8"});
  // The rules a scene file's reader states are the scene's own.
  scene = calder::builtin_scene("example-2.9");
  scene.world.arithmetic = calder::Arithmetic::float64;
  calder::test::expect_error([&] { scene.validate(); }, {"arithmetic other than book"});
  scene = calder::builtin_scene("example-2.9");
  scene.bodies[0].mass = calder::Draw::linear(1.0, -1.0);
  calder::test::expect_error([&] { scene.validate(); }, {"masses must be > 0"});
  calder::WorldDef def;
  def.threads = 1025;
  calder::test::expect_error([&] { calder::World w(def); }, {"threads must be between 0 and 1024"});
}

}  // namespace
