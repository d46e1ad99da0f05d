// SPDX-License-Identifier: MIT
// Unit tests of the calder command's parts (apps/calder): flag parsing, the
// --state reader, atomic output files, JSON trajectories, the verbs in process.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <new>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../../src/output/output.hpp"
#include "calder/calder.hpp"
#include "calder/nbody.hpp"
#include "cli.hpp"
#include "errors.hpp"
#include "output_file.hpp"
#include "output_policy.hpp"
#include "parse.hpp"
#include "progress.hpp"
#include "run_command.hpp"
#include "run_options.hpp"
#include "state_csv.hpp"
#include "trajectory_json.hpp"

namespace fs = std::filesystem;
using calder::app::InputError;

namespace {

// A fresh folder under the system's temporary folder, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("calder-cli-" + std::string(info->test_suite_name()) + "-" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
  [[nodiscard]] std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_))
      names.push_back(e.path().filename().string());
    return names;
  }

 private:
  fs::path path_;
};

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no exception)";
}

struct Result {
  int status;
  std::string out;
  std::string err;
};

Result cli(std::vector<const char*> args) {
  args.insert(args.begin(), "calder");
  std::ostringstream out;
  std::ostringstream err;
  const int status = calder::app::main(static_cast<int>(args.size()), args.data(), out, err);
  return {status, out.str(), err.str()};
}

}  // namespace

// --- flags ------------------------------------------------------------------------

TEST(CliParse, Numbers) {
  EXPECT_EQ(calder::app::to_int64("42"), 42);
  EXPECT_EQ(calder::app::to_int64("+42"), 42);
  EXPECT_EQ(calder::app::to_int64("-7"), -7);
  EXPECT_FALSE(calder::app::to_int64("4x"));
  EXPECT_FALSE(calder::app::to_int64(""));
  EXPECT_FALSE(calder::app::to_int64("+-1"));
  EXPECT_FALSE(calder::app::to_int64("99999999999999999999"));
  EXPECT_EQ(calder::app::to_double("0.1"), 0.1);
  EXPECT_EQ(calder::app::to_double("30.599999999999998"), 30.599999999999998);
  EXPECT_EQ(calder::app::to_double("1e-3"), 1e-3);
  EXPECT_TRUE(std::isnan(*calder::app::to_double("nan")));
  EXPECT_FALSE(calder::app::to_double("1e400"));
  EXPECT_FALSE(calder::app::to_double("1.5.2"));
  EXPECT_FALSE(calder::app::to_double(" 1"));
}

TEST(CliParse, Flags) {
  using namespace calder::app;
  EXPECT_EQ(parse_frames("--frames", "0"), 0);
  EXPECT_EQ(parse_frames("--frames", "10000000"), 10'000'000);
  EXPECT_EQ(message_of([] { parse_frames("--frames", "-1"); }),
            "--frames: expected an integer from 0 to 10000000, got '-1'");
  EXPECT_THROW(parse_frames("--frames", "10000001"), InputError);
  EXPECT_EQ(parse_dt("--dt", "0.5"), 0.5);
  for (const char* bad : {"0", "-1", "nan", "inf", "x"}) {
    EXPECT_THROW(parse_dt("--dt", bad), InputError) << bad;
  }
  EXPECT_EQ(parse_seed("--seed", "4294967295"), 4294967295u);
  EXPECT_THROW(parse_seed("--seed", "4294967296"), InputError);
  EXPECT_THROW(parse_seed("--seed", "-1"), InputError);
}

TEST(CliParse, FrameRanges) {
  using namespace calder::app;
  const auto r = parse_frame_range("--mouse-pressed", "100-160");
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].first, 100);
  EXPECT_EQ(r[0].last, 160);
  EXPECT_EQ(parse_frame_range("--mouse-pressed", "5-5")[0].last, 5);
  EXPECT_TRUE(parse_frame_range("--mouse-pressed", "none").empty());
  for (const char* bad : {"100", "100:160", "0-5", "-1-5", "160-100", "a-b", "1-", "-", "1-2-3"}) {
    EXPECT_THROW(parse_frame_range("--mouse-pressed", bad), InputError) << bad;
  }
  const calder::Vec2 p = parse_point("--mouse", "320,120.5");
  EXPECT_EQ(p.x, 320.0);
  EXPECT_EQ(p.y, 120.5);
  for (const char* bad : {"320", "1,nan", "a,b", "1;2"}) {
    EXPECT_THROW(parse_point("--mouse", bad), InputError) << bad;
  }
}

TEST(CliParse, ApplyFlags) {
  calder::app::InputOptions options;
  options.scene = "example-2.1";
  options.frames = "12";
  options.dt = "0.5";
  options.seed = "3";
  options.mouse_pressed = {"2-3", "7-9"};
  options.mouse = "1,2";
  const calder::app::PreparedInput input = calder::app::prepare_input(options);
  EXPECT_EQ(input.scene.frames, 12);
  EXPECT_EQ(input.scene.world.dt, 0.5);
  EXPECT_EQ(input.effective_seed(), 3u);
  ASSERT_EQ(input.scene.input.mouse_pressed.size(), 2u);
  EXPECT_EQ(input.scene.input.mouse_pressed[1].first, 7);
  EXPECT_EQ(input.scene.input.mouse, (calder::Vec2{1, 2}));
  const calder::Simulation sim = calder::app::start_simulation(input);
  EXPECT_EQ(sim.world().dt(), 0.5);
}

// --- --state ----------------------------------------------------------------------

TEST(CliState, ReadsRowsExactly) {
  std::istringstream in(
      "x,y,vx,vy,mass,radius\r\n1,2,3,4,5,6\r\n\n 30.599999999999998 , -0.1,0,0,1e-3,0\n");
  const auto rows = calder::app::parse_state_csv(in, "s.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].mass, 5.0);
  EXPECT_EQ(rows[0].radius, 6.0);
  EXPECT_EQ(rows[1].x, 30.599999999999998);
  EXPECT_EQ(rows[1].y, -0.1);
  EXPECT_EQ(rows[1].mass, 1e-3);
}

TEST(CliState, HeaderOnlyIsNoBodies) {
  std::istringstream in("x,y,vx,vy,mass\n");
  EXPECT_TRUE(calder::app::parse_state_csv(in, "s.csv").empty());
}

TEST(CliState, ErrorsNameFileAndLine) {
  const auto error = [](const std::string& text) {
    return message_of([&] {
      std::istringstream in(text);
      calder::app::parse_state_csv(in, "s.csv");
    });
  };
  EXPECT_EQ(error(""),
            "s.csv:1: empty file: expected the header 'x,y,vx,vy,mass' or 'x,y,vx,vy,mass,radius'");
  EXPECT_EQ(error("x,y,vx,vy,m\n"),
            "s.csv:1: expected the header 'x,y,vx,vy,mass' or 'x,y,vx,vy,mass,radius', got "
            "'x,y,vx,vy,m'");
  EXPECT_EQ(error("x,y,vx,vy,mass\n1,2,3,4\n"),
            "s.csv:2: expected 5 fields (x,y,vx,vy,mass), got 4");
  EXPECT_EQ(error("x,y,vx,vy,mass\n1,2,3,4,5,6\n"),
            "s.csv:2: expected 5 fields (x,y,vx,vy,mass), got 6");
  EXPECT_EQ(error("x,y,vx,vy,mass\n1,2,3,4,1\n1,,3,4,1\n"), "s.csv:3: y: '' is not a number");
  EXPECT_EQ(error("x,y,vx,vy,mass\ninf,2,3,4,1\n"), "s.csv:2: x must be finite (got 'inf')");
  EXPECT_EQ(error("x,y,vx,vy,mass\n1,2,3,4,0\n"), "s.csv:2: mass must be > 0 (got 0)");
  EXPECT_EQ(error("x,y,vx,vy,mass,radius\n1,2,3,4,1,-1\n"),
            "s.csv:2: radius must be >= 0 (got -1)");
}

TEST(CliState, RadiusFromTheScene) {
  const calder::Scene scene = calder::builtin_scene("example-2.2");  // radius = mass * 8
  std::vector<calder::app::StateRow> rows(2);
  rows[0].mass = 2;
  rows[1].mass = 3;
  rows[1].radius = 1.5;
  const auto bodies = calder::app::bodies_from_state(rows, scene);
  EXPECT_EQ(bodies[0].radius, 16.0);
  EXPECT_EQ(bodies[1].radius, 1.5);
}

// --- output files -------------------------------------------------------------------

TEST(CliOutputFile, CommitReplacesTheTarget) {
  TempDir dir;
  const std::string path = dir.file("out.csv");
  std::ofstream(path) << "old\n";
  {
    calder::app::OutputFile file(path);
    file.stream() << "new\n";
    EXPECT_EQ(read_all(path), "old\n");   // untouched until commit
    EXPECT_EQ(dir.entries().size(), 2u);  // the target and the temporary
    file.commit();
  }
  EXPECT_EQ(read_all(path), "new\n");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.csv"});
  // The existing file's mode (0666 less the umask, as ofstream made it), not mkstemp's 0600.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  EXPECT_EQ(static_cast<unsigned>(fs::status(path).permissions()), 0666u & ~mask);
}

TEST(CliOutputFile, NoCommitLeavesNothing) {
  TempDir dir;
  {
    calder::app::OutputFile file(dir.file("out.csv"));
    file.stream() << "partial";
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliOutputFile, BadPaths) {
  TempDir dir;
  EXPECT_EQ(message_of([&] { calder::app::OutputFile f(dir.file("no/out.csv")); }),
            dir.file("no/out.csv") + ": cannot create the file: the folder '" + dir.file("no/") +
                "' does not exist");
  EXPECT_EQ(message_of([&] { calder::app::OutputFile f(dir.file("")); }),
            dir.file("") + ": is a directory, not a file");
  EXPECT_TRUE(dir.entries().empty());
}

// --- JSON ---------------------------------------------------------------------------

TEST(CliJson, RoundTripsNumbers) {
  calder::World world;
  world.add_body({.position = {0.1, 30.599999999999998}, .velocity = {-1e-300, 2}, .mass = 1});
  std::ostringstream out;
  calder::app::TrajectoryJsonWriter writer(
      out, {.scene = "a \"quoted\" name", .frames = 0, .bodies = 1, .dt = 0.25, .seed = 7});
  writer.write(0, world);
  writer.finish();
  const auto doc = nlohmann::json::parse(out.str());
  EXPECT_EQ(doc["scene"], "a \"quoted\" name");
  EXPECT_EQ(doc["dt"].get<double>(), 0.25);
  EXPECT_EQ(doc["seed"], 7);
  ASSERT_EQ(doc["rows"].size(), 1u);
  EXPECT_EQ(doc["rows"][0][2].get<double>(), 0.1);
  EXPECT_EQ(doc["rows"][0][3].get<double>(), 30.599999999999998);
  EXPECT_EQ(doc["rows"][0][4].get<double>(), -1e-300);
}

TEST(CliJson, EmptyWorld) {
  std::ostringstream out;
  calder::app::TrajectoryJsonWriter writer(out, {.scene = "x"});
  writer.write(0, calder::World{});
  writer.finish();
  EXPECT_TRUE(nlohmann::json::parse(out.str())["rows"].empty());
}

TEST(CliRun, FormatAndRowLimit) {
  using calder::app::TrajectoryFormat;
  EXPECT_EQ(calder::app::trajectory_format(std::nullopt, "a.JSON"), TrajectoryFormat::json);
  EXPECT_EQ(calder::app::trajectory_format(std::nullopt, "a.csv"), TrajectoryFormat::csv);
  EXPECT_EQ(calder::app::trajectory_format("csv", "a.json"), TrajectoryFormat::csv);
  EXPECT_NO_THROW(calder::app::check_trajectory_rows(49'999'999, 1));
  EXPECT_NO_THROW(calder::app::check_trajectory_rows(0, 50'000'000));
  EXPECT_THROW(calder::app::check_trajectory_rows(50'000'000, 1), InputError);
  EXPECT_THROW(calder::app::check_trajectory_rows(10'000'000, 10'000'000), InputError);
}

// --- the verbs, in process ----------------------------------------------------------

TEST(CliMain, ListsEveryBuiltinScene) {
  const Result r = cli({"list"});
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.err, "");
  for (const auto& s : calder::builtin_scenes()) {
    EXPECT_NE(r.out.find(s.name + "  "), std::string::npos) << s.name;
    EXPECT_NE(r.out.find(s.description), std::string::npos) << s.name;
  }
}

TEST(CliMain, UsageErrorsExit2OnOneLine) {
  for (const std::vector<const char*>& args :
       std::vector<std::vector<const char*>>{{},
                                             {"fly"},
                                             {"run"},
                                             {"run", "example-2.1", "--frames"},
                                             {"run", "example-2.1", "--nope"},
                                             {"run", "example-2.1", "extra"},
                                             {"list", "extra"},
                                             {"run", "example-2.1", "--format", "json"}}) {
    const Result r = cli(args);
    std::string shown;
    for (const char* a : args) shown += std::string(" ") + a;
    EXPECT_EQ(r.status, 2) << shown;
    EXPECT_EQ(r.out, "") << shown;
    EXPECT_EQ(r.err.rfind("calder: ", 0), 0u) << shown << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << shown << ": " << r.err;
  }
}

TEST(CliMain, HelpAndVersionExit0) {
  for (const std::vector<const char*>& args : std::vector<std::vector<const char*>>{
           {"--help"}, {"run", "--help"}, {"list", "--help"}, {"--version"}}) {
    const Result r = cli(args);
    EXPECT_EQ(r.status, 0) << args.back();
    EXPECT_EQ(r.err, "");
    EXPECT_FALSE(r.out.empty());
  }
}

TEST(CliMain, NegativeFramesReachTheRangeCheck) {
  const Result r = cli({"run", "example-2.1", "--frames", "-1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "calder: --frames: expected an integer from 0 to 10000000, got '-1'\n");
}

namespace {

// The summary's "state hash" line of a built-in scene run here for `frames`.
std::string hash_line(const std::string& scene, int frames, std::optional<std::uint32_t> seed) {
  calder::Simulation sim(calder::builtin_scene(scene), seed);
  for (int i = 0; i < frames; ++i) sim.step();
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx",
                static_cast<unsigned long long>(calder::state_hash(sim.world())));
  return std::string("state hash        ") + hash + "\n";
}

}  // namespace

TEST(CliMain, SummaryHashEqualsTheWorldsHash) {
  const Result r = cli({"run", "example-2.7", "--frames", "50", "--seed", "4"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find(hash_line("example-2.7", 50, 4u)), std::string::npos) << r.out;
}

TEST(CliMain, RuntimeFailureExits1) {
  TempDir dir;
  std::ofstream(dir.file("state.csv")) << "x,y,vx,vy,mass\n1e308,0,1.7e308,0,1\n";
  const std::string state = dir.file("state.csv");
  const std::string out = dir.file("out.csv");
  const Result r =
      cli({"run", "example-2.8", "--state", state.c_str(), "--trajectory", out.c_str()});
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err.rfind("calder: example-2.8: frame 1: ", 0), 0u) << r.err;
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"state.csv"});
}

// --- run_cli: the one top level of calder and calder-bench ---------------------------

namespace {

// run_cli's exit status and stderr when the command throws `error`.
template <typename Throw>
std::pair<int, std::string> run_cli_with(Throw&& throw_it) {
  std::ostringstream out;
  std::ostringstream err;
  const int status = calder::app::run_cli("prog", out, err, throw_it);
  return {status, err.str()};
}

}  // namespace

TEST(CliRunCli, MapsEachKindToItsExitCode) {
  using calder::app::exit_failure;
  using calder::app::exit_usage;
  const auto usage = run_cli_with([] { throw calder::InputError("prog: a.toml:3: bad\nkey"); });
  EXPECT_EQ(usage, std::make_pair(exit_usage, std::string("prog: a.toml:3: bad key\n")));
  EXPECT_EQ(run_cli_with([] { throw calder::InvalidArgument("mass"); }).first, exit_usage);
  EXPECT_EQ(run_cli_with([] { throw calder::Error("plain"); }).first, exit_usage);
  const auto failed = run_cli_with([] { throw calder::RunError("rain: frame 3: NaN"); });
  EXPECT_EQ(failed, std::make_pair(exit_failure, std::string("prog: rain: frame 3: NaN\n")));
  EXPECT_EQ(run_cli_with([] { throw std::bad_alloc(); }),
            std::make_pair(exit_failure, std::string("prog: out of memory\n")));
  EXPECT_EQ(run_cli_with([] { throw std::runtime_error("other"); }).first, exit_failure);
  EXPECT_EQ(run_cli_with([] {}), std::make_pair(calder::app::exit_success, std::string()));
}

TEST(CliRunCli, AStepFailureIsARunFailureNamingSourceAndFrame) {
  try {
    calder::app::throw_run_failure(calder::InvalidArgument("body 2 is NaN"), "rain", 12);
    ADD_FAILURE() << "expected RunError";
  } catch (const calder::RunError& e) {
    EXPECT_STREQ(e.what(), "rain: frame 12: body 2 is NaN");
  }
}

// main keeps one parser for the process: no flag of an earlier call, whole
// or cut short by an error, carries over to the next.
TEST(CliMain, EachCallStartsFromTheDefaults) {
  ASSERT_EQ(cli({"run", "example-2.7", "--frames", "50", "--seed", "4"}).status, 0);
  EXPECT_EQ(cli({"run", "example-2.7", "--frames", "7", "--seed", "9", "--no-such-flag"}).status,
            2);
  const Result r = cli({"run", "example-2.7", "--frames", "3"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find(hash_line("example-2.7", 3, std::nullopt)), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("frames            3\n"), std::string::npos) << r.out;
  EXPECT_EQ(cli({"list", "--frames"}).status, 2);  // `run`'s flags stay with `run`
}

// --- the work budget: every cost that grows with the input ---------------------------

// Property: the budget tracks what Barnes-Hut really evaluates. For random
// systems (sizes, opening angles, a share of the bodies piled on one point),
// the solver's own count of pair interactions stays within a fixed factor of
// barnes_hut_work + coincident_work: a cost that grew without the budget
// growing (theta = 0 counted as n log n, coincident bodies ignored) breaks it.
TEST(CliWork, BudgetBoundsBarnesHutsInteractions) {
  std::uint64_t state = 12345;
  const auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11U) / 9007199254740992.0;  // [0, 1)
  };
  double worst = 0.0;
  for (int trial = 0; trial < 24; ++trial) {
    const auto n = static_cast<std::size_t>(200 + next() * 3800);
    const double theta = trial % 4 == 0 ? 0.0 : next();
    const double piled = trial % 3 == 0 ? next() : 0.0;  // share of bodies at one point
    std::vector<double> x(n), y(n), mass(n, 1.0), ax(n, 0.0), ay(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const bool at_point = static_cast<double>(i) < piled * static_cast<double>(n);
      x[i] = at_point ? 100.0 : next() * 640.0;
      y[i] = at_point ? 100.0 : next() * 360.0;
    }
    calder::nbody::BarnesHutOptions options;
    options.theta = theta;
    options.softening = 1.0;
    options.threads = 1;
    calder::nbody::BarnesHutStats stats;
    calder::nbody::barnes_hut_accelerations(x, y, mass, ax, ay, options, &stats);
    const double budget = calder::app::barnes_hut_work(static_cast<double>(n), theta) +
                          calder::app::coincident_work(x, y);
    const double ratio = static_cast<double>(stats.interactions) / budget;
    worst = std::max(worst, ratio);
    EXPECT_LE(ratio, 64.0) << "n " << n << ", theta " << theta << ", piled " << piled;
  }
  RecordProperty("worst_ratio", std::to_string(worst));
}

TEST(CliWork, CoincidentBodiesAreCounted) {
  std::vector<double> x(1000, 1000.5), y(1000, 5.0);
  EXPECT_EQ(calder::app::coincident_work(x, y), 1e6);                   // one cell of 1000
  for (std::size_t i = 0; i < 500; ++i) x[i] = static_cast<double>(i);  // 500 spread, 500 piled
  EXPECT_EQ(calder::app::coincident_work(x, y), 500.0 * 500.0);
  std::vector<double> spread(1000);
  for (std::size_t i = 0; i < spread.size(); ++i) spread[i] = static_cast<double>(i);
  EXPECT_EQ(calder::app::coincident_work(spread, spread), 0.0);
}

TEST(CliWork, ThetaZeroIsTheDirectSum) {
  EXPECT_EQ(calder::app::barnes_hut_work(20000.0, 0.0), 20000.0 * 20000.0);
  const double n = 1e6;
  EXPECT_NEAR(calder::app::barnes_hut_work(n, calder::kDefaultTheta), n * std::log2(n), 1.0);
  // Smaller angles cost more, never more than all pairs; larger ones no less
  // than the default's (the leaves' direct sums).
  EXPECT_EQ(calder::app::barnes_hut_work(n, 1.0), calder::app::barnes_hut_work(n, 0.7));
  double last = 0.0;
  for (const double theta : {1.0, 0.7, 0.5, 0.3, 0.1, 0.01, 0.0}) {
    const double work = calder::app::barnes_hut_work(n, theta);
    EXPECT_GE(work, last);
    EXPECT_LE(work, n * n);
    last = work;
  }
}

TEST(CliWork, FieldsAndScriptedInputAreCounted) {
  calder::Scene scene;
  scene.frames = 1000;
  const double one = calder::app::run_work(scene, 10);
  for (int k = 0; k < 100; ++k) scene.fields.push_back({calder::Gravity{}});
  EXPECT_EQ(calder::app::run_work(scene, 10), one * 100.0);
  for (int k = 0; k < 5000; ++k) scene.input.mouse_pressed.push_back({2 * k + 1, 2 * k + 1});
  EXPECT_EQ(calder::app::run_work(scene, 10), (10.0 * 100.0 + 5000.0) * 1000.0);
}

// --- threads ---------------------------------------------------------------------------

TEST(CliThreads, CappedToTheProcessors) {
  calder::Scene scene;
  scene.world.threads = 1024;
  calder::MutualAttraction mutual;
  mutual.threads = 1024;
  scene.fields.push_back({mutual});
  calder::app::limit_threads(scene, "t.toml");
  const int cpus = calder::app::usable_threads();
  EXPECT_EQ(scene.world.threads, cpus);
  EXPECT_EQ(std::get<calder::MutualAttraction>(scene.fields[0].field).threads, cpus);
  scene.world.threads = 0;  // "every core" stays as it is
  calder::app::limit_threads(scene, "t.toml");
  EXPECT_EQ(scene.world.threads, 0);
}

// --- diagnostics: bounded, labelled, never inf or nan as a result ------------------------

TEST(CliSummary, BoundedPotentialIsExactBelowTheBoundAndUnbiasedAbove) {
  calder::Scene scene;
  scene.world.width = 640;
  scene.world.height = 360;
  calder::BodyGroup group;
  group.count = 3000;
  group.x = calder::Draw::uniform(0.0, 640.0);
  group.y = calder::Draw::uniform(0.0, 360.0);
  scene.bodies.push_back(group);
  scene.fields.push_back({calder::MutualAttraction{}});
  const calder::Simulation simulation(scene);
  const double exact = calder::potential_energy(simulation.world());
  const calder::PotentialEstimate all =
      calder::bounded_potential_energy(simulation.world(), std::uint64_t{1} << 30);
  EXPECT_TRUE(all.exact);
  EXPECT_EQ(all.value, exact);  // the same sum, in the same order
  const calder::PotentialEstimate some =
      calder::bounded_potential_energy(simulation.world(), 200000);
  EXPECT_FALSE(some.exact);
  EXPECT_EQ(some.pairs_summed, 200000u);
  EXPECT_EQ(some.pairs_total, 3000u * 2999u / 2u);
  EXPECT_NEAR(some.value / exact, 1.0, 0.02);  // 2e5 samples of a smooth sum
}

// Property: random finite but huge states either give a summary of finite
// numbers, or fail with exit 1 and one line; inf and nan never print.
TEST(CliSummary, OverflowFailsNeverPrintsInfOrNan) {
  TempDir dir;
  std::uint64_t state = 99;
  const auto pick = [&state](std::initializer_list<const char*> options) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return *(options.begin() + (state >> 33U) % options.size());
  };
  int failures = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::string name = std::to_string(trial);
    name += ".toml";
    const std::string path = dir.file(name);
    std::ofstream(path) << "frames = " << pick({"0", "1", "2"})
                        << "\n[[bodies]]\nmass = " << pick({"1", "1e10", "1e300"})
                        << "\nposition = [" << pick({"0", "1e300"}) << ", "
                        << pick({"1", "1e300", "-1e300"}) << "]\nvelocity = ["
                        << pick({"0", "1e300", "1e154"}) << ", " << pick({"0", "1e200"})
                        << "]\n[[fields]]\ntype = \"gravity\"\ng = [0, 0.1]\nscale_by_mass = "
                        << pick({"true", "false"}) << "\n";
    const Result r = cli({"run", path.c_str()});
    const bool printed_bad =
        r.out.find("inf") != std::string::npos || r.out.find("nan") != std::string::npos;
    EXPECT_FALSE(printed_bad) << r.out;
    if (r.status == 0) continue;
    ++failures;
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_GT(failures, 0);  // the property was exercised
}

// --- the output policy -------------------------------------------------------------------

// Property: for random spellings of random paths (through "./", "sub/..",
// links), an output is refused exactly when it is the same file as an input or
// as the other output (the truth: std::filesystem::equivalent), and nothing
// refused is changed.
TEST(CliOutputPolicy, SameFileRefusedWhateverTheSpelling) {
  TempDir dir;
  fs::create_directory(dir.file("sub"));
  std::ofstream(dir.file("scene.toml")) << "frames = 2\n[[bodies]]\nmass = 1\nposition = [1, 1]\n";
  std::ofstream(dir.file("other.csv")) << "old\n";
  fs::create_symlink(dir.file("scene.toml"), dir.file("link.toml"));
  const std::vector<std::string> names = {"scene.toml", "./scene.toml", "sub/../scene.toml",
                                          "link.toml",  "other.csv",    "sub/../other.csv",
                                          "new.csv",    "./new.csv"};
  std::uint64_t state = 7;
  for (int trial = 0; trial < 40; ++trial) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const std::string out = dir.file(names[(state >> 33U) % names.size()]);
    const std::string scene = dir.file("scene.toml");
    const std::string before = read_all(scene);
    const Result r = cli({"run", scene.c_str(), "--trajectory", out.c_str()});
    std::error_code ec;
    const bool same = fs::equivalent(out, scene, ec);
    if (same) {
      EXPECT_EQ(r.status, 2) << out;
      EXPECT_NE(r.err.find("is the scene file"), std::string::npos) << r.err;
    } else {
      EXPECT_EQ(r.status, 0) << out << ": " << r.err;
    }
    EXPECT_EQ(read_all(scene), before);
    EXPECT_TRUE(fs::is_symlink(dir.file("link.toml")));
  }
}

TEST(CliOutputPolicy, ForeignOwnerRefusalOnlyInStickyFolders) {
  TempDir dir;
  std::ofstream(dir.file("mine.csv")) << "x\n";
  EXPECT_EQ(calder::output::foreign_owner_refusal(dir.file("mine.csv")), "");  // ours
  EXPECT_EQ(calder::output::foreign_owner_refusal(dir.file("missing.csv")), "");
  if (::geteuid() == 0) {  // only root can give a file away
    ::chmod(dir.file("").c_str(), 01777);
    ASSERT_EQ(::lchown(dir.file("mine.csv").c_str(), 65534, 65534), 0);
    EXPECT_NE(calder::output::foreign_owner_refusal(dir.file("mine.csv")).find("another user's"),
              std::string::npos);
    ::chmod(dir.file("").c_str(), 0755);  // not sticky: the file's owner doesn't matter
    EXPECT_EQ(calder::output::foreign_owner_refusal(dir.file("mine.csv")), "");
  }
}

TEST(CliOutputPolicy, WriteProtectedAndDanglingLinksRefused) {
  TempDir dir;
  std::ofstream(dir.file("ro.csv")) << "old\n";
  fs::permissions(dir.file("ro.csv"),
                  fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  EXPECT_NE(
      message_of([&] { calder::app::OutputFile f(dir.file("ro.csv")); }).find("write-protected"),
      std::string::npos);
  fs::create_symlink(dir.file("nothing.csv"), dir.file("dangling.csv"));
  EXPECT_NE(message_of([&] {
              calder::app::OutputFile f(dir.file("dangling.csv"));
            }).find("a symbolic link to a missing file"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(dir.file("nothing.csv")));
  EXPECT_EQ(read_all(dir.file("ro.csv")), "old\n");
}

// Property: paths of random bytes in --gif and --png: every line render
// prints (a report or an error) is one line without control characters.
TEST(CliOutputPolicy, ReportedPathsAreEscaped) {
  TempDir dir;
  std::uint64_t state = 3;
  int written = 0;
  for (int trial = 0; trial < 12; ++trial) {
    std::string name;
    for (int k = 0; k < 12; ++k) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      char c = static_cast<char>((state >> 33U) % 128U);
      if (c == '\0' || c == '/') c = '\n';
      name += c;
    }
    const std::string gif = dir.file(name + ".gif");
    const std::string png = dir.file(name);
    const Result r =
        cli({"render", "example-2.1", "--frames", "1", "--gif", gif.c_str(), "--png", png.c_str()});
    for (const std::string* text : {&r.out, &r.err}) {
      for (const char c : *text) {
        EXPECT_FALSE(c != '\n' && (static_cast<unsigned char>(c) < 0x20 || c == 0x7f))
            << "trial " << trial << ": " << *text;
      }
    }
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), r.status == 0 ? 2 : 0);
    EXPECT_EQ(r.out.find("\ncalder:"), std::string::npos);
    written += r.status == 0 ? 1 : 0;
  }
  EXPECT_GT(written, 0);  // some renders succeeded and reported their paths
}

// --- signals: a long computation is cut short -------------------------------------------

// A computation that never checks for a signal still ends within the grace
// time, with 128 + SIGTERM, its registered temporary removed.
TEST(CliInterruptDeathTest, WatchdogEndsALongComputation) {
  TempDir dir;
  const std::string temp = dir.file(".out.tmp-x");
  EXPECT_EXIT(
      {
        const calder::app::InterruptGuard guard;
        {
          const std::lock_guard<std::mutex> lock(calder::output::temporaries_lock());
          std::ofstream(temp) << "partial";
          calder::output::register_temporary(temp, false);
        }
        std::raise(SIGTERM);
        volatile double sink = 0.0;
        for (long k = 0;; ++k) sink = sink + 1.0;  // a long frame: never checks
      },
      ::testing::ExitedWithCode(128 + SIGTERM), "calder: interrupted");
  EXPECT_FALSE(fs::exists(temp));
}

// --- PNG frames: all or none ------------------------------------------------------------

namespace {

// Every entry under `root` (relative path -> contents, "<dir>" for folders).
std::vector<std::pair<std::string, std::string>> tree_of(const std::string& root) {
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string name = fs::relative(e.path(), root).string();
    entries.emplace_back(name, e.is_directory() ? std::string("<dir>") : read_all(e.path()));
  }
  std::sort(entries.begin(), entries.end());
  return entries;
}

}  // namespace

// Property: whatever an existing --png folder holds (frames of an earlier
// render, other files, folders), a render that succeeds leaves exactly its own
// frames plus the other entries untouched, and a render that fails midway
// leaves the folder exactly as it was; nothing is left beside it.
TEST(CliFrames, AllOrNoneWhateverTheFolderHolds) {
  TempDir dir;
  const std::string state = dir.file("state.csv");
  std::ofstream(state) << "x,y,vx,vy,mass\n1e308,0,1.7e308,0,1\n";  // overflows in step 1
  std::uint64_t seed = 11;
  const auto next = [&seed](std::uint64_t range) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return (seed >> 33U) % range;
  };
  for (int trial = 0; trial < 8; ++trial) {
    const std::string frames = dir.file("frames");
    fs::remove_all(frames);
    fs::create_directory(frames);
    const std::uint64_t old_frames = next(6);
    for (std::uint64_t k = 0; k < old_frames; ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "frame-%06llu.png", static_cast<unsigned long long>(k));
      std::ofstream(frames + "/" + name) << "old frame " << k;
    }
    if (next(2) == 1) std::ofstream(frames + "/notes.txt") << "keep " << trial;
    if (next(2) == 1) {
      fs::create_directory(frames + "/sub");
      std::ofstream(frames + "/sub/deep.txt") << "deep";
    }
    const auto before = tree_of(frames);
    const bool fail = next(2) == 1;
    const std::string count = std::to_string(next(4));
    const Result r = fail ? cli({"render", "example-2.8", "--state", state.c_str(), "--png",
                                 frames.c_str(), "-q"})
                          : cli({"render", "example-2.1", "--frames", count.c_str(), "--png",
                                 frames.c_str(), "-q"});
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(dir.file(""))) {
      const std::string name = e.path().filename().string();
      if (name != "frames" && name != "state.csv") left.push_back(name);
    }
    EXPECT_TRUE(left.empty()) << "trial " << trial << ": " << left.front();
    if (fail) {
      EXPECT_EQ(r.status, 1) << r.err;
      EXPECT_EQ(tree_of(frames), before) << "trial " << trial;
      continue;
    }
    ASSERT_EQ(r.status, 0) << r.err;
    auto expected = before;
    std::erase_if(expected, [](const auto& e) { return e.first.starts_with("frame-"); });
    auto after = tree_of(frames);
    std::size_t new_frames = 0;
    std::erase_if(after, [&](const auto& e) {
      if (!e.first.starts_with("frame-")) return false;
      EXPECT_EQ(e.second.substr(1, 3), "PNG") << e.first;  // this render's, not an old one
      ++new_frames;
      return true;
    });
    EXPECT_EQ(after, expected) << "trial " << trial;
    EXPECT_EQ(new_frames, std::stoul(count) + 1) << "trial " << trial;
  }
}
