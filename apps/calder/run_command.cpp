// SPDX-License-Identifier: MIT
#include "run_command.hpp"

#include <sys/stat.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <limits>
#include <string>

#include "calder/error.hpp"
#include "calder/trajectory.hpp"
#include "calder/world.hpp"
#include "devices_command.hpp"
#include "errors.hpp"
#include "output_file.hpp"
#include "output_policy.hpp"
#include "progress.hpp"
#include "summary.hpp"
#include "trajectory_json.hpp"

namespace calder::app {

namespace {

template <class Writer>
void write_run(Simulation& simulation, const PreparedInput& input, Writer& writer, OutputFile& file,
               const std::ostream& stream, const std::function<void(std::int64_t)>& after_frame) {
  writer.write(simulation.frame(), simulation.world());  // 0, or a resumed snapshot's frame
  file.check_stream(stream);
  run_frames(simulation, input.scene.frames, input.source, [&](std::int64_t frame) {
    writer.write(frame, simulation.world());
    after_frame(frame);         // a signal first: SIGPIPE also fails the write
    file.check_stream(stream);  // the first failed write stops the run
  });
}

// Every output of the run (--trajectory, --save, --archive) by the output
// policy, against its inputs (the scene file or snapshot, the --state file)
// and one another, before anything is created or truncated.
void check_run_outputs(const RunOptions& options, const PreparedInput& input) {
  std::vector<NamedPath> inputs;
  struct stat info {};
  if (::stat(input.source.c_str(), &info) == 0) {
    inputs.push_back({input.resumed ? "the snapshot" : "the scene file", input.source});
  }
  if (input.state_path) inputs.push_back({"--state", *input.state_path});
  std::vector<NamedPath> outputs;
  if (options.trajectory) outputs.push_back({"--trajectory", *options.trajectory});
  add_snapshot_outputs(options.snapshot, outputs);
  check_outputs(inputs, outputs);
}

// Over this many bytes written a run is refused (exit 2) unless
// --no-work-limit is given.
constexpr double max_run_bytes = 16e9;
// A trajectory row: frame and body, four numbers in their shortest form.
constexpr double trajectory_row_bytes = 96.0;

// The budget of the bytes a run will write: its trajectory and snapshots.
void check_bytes_written(const RunOptions& options, const PreparedInput& input,
                         const Simulation& simulation) {
  if (input.no_work_limit) return;
  const std::int64_t frames = input.scene.frames;
  const double snapshots =
      static_cast<double>(snapshot_bytes_written(options.snapshot, simulation, frames));
  const double trajectory = options.trajectory
                                ? static_cast<double>(frames - simulation.frame() + 1) *
                                      static_cast<double>(simulation.world().body_count()) *
                                      trajectory_row_bytes
                                : 0.0;
  const double bytes = snapshots + trajectory;
  if (bytes <= max_run_bytes) return;
  char text[64];
  std::snprintf(text, sizeof text, bytes < 100e9 ? "about %.1f GB" : "about %.0f GB", bytes / 1e9);
  throw InputError(
      detail::printable(input.source, 240) + ": this run would write " + text +
      (snapshots > trajectory ? " of snapshots (--archive, --save)" : " of trajectory") +
      ", over the budget of 16 GB; use a larger --every or fewer --frames, or "
      "--no-work-limit to write it anyway");
}

// The energy error of a run: measured every frame when that is cheap (and
// every --energy-every frames), a warning the first time it passes the
// threshold, a RunError at the end with --fail-on-energy.
class EnergyMonitor {
 public:
  EnergyMonitor(const Simulation& simulation, const RunOptions& options, std::ostream& lines,
                std::ostream& err)
      : watch_(simulation.world(), options.energy_threshold.value_or(kDefaultEnergyThreshold),
               start_energy(simulation)),
        warn_(options.energy_threshold.has_value() || newtonian(simulation.world())),
        every_(options.energy_every),
        fail_(options.fail_on_energy),
        cheap_(potential_energy_cost(simulation.world(), summary_potential_pairs) <=
               kEveryFrameTerms),
        lines_(lines),
        err_(err) {}
  void after_frame(const Simulation& simulation) {
    const std::int64_t frame = simulation.frame();
    const bool listed = every_ > 0 && frame % every_ == 0;
    if (!watch_.active() || !(cheap_ || listed)) return;
    if (watch_.observe(simulation.world(), frame) && warn_) {
      err_ << "calder: warning: relative energy error " << format_number(watch_.last_error())
           << " passed " << format_number(watch_.threshold()) << " at frame " << frame
           << " (t = " << format_number(simulation.world().time()) << ")\n";
    }
    if (listed) {
      lines_ << "energy frame " << frame << " t " << format_number(simulation.world().time())
             << " total " << format_number(watch_.last_energy()) << " relative error "
             << format_number(watch_.last_error()) << '\n';
    }
  }
  void finish(const std::string& source) const {
    if (fail_ && warn_ && watch_.first_frame_over() >= 0) {
      throw RunError(source + ": the relative energy error passed " +
                     format_number(watch_.threshold()) + " at frame " +
                     std::to_string(watch_.first_frame_over()) + " (--fail-on-energy)");
    }
  }
  [[nodiscard]] const EnergyWatch& watch() const { return watch_; }

 private:
  // Up to this many pair terms the error is measured after every frame.
  static constexpr std::uint64_t kEveryFrameTerms = 100'000;
  // Warn unasked only about Newton's unclamped law: the book's clamped laws
  // at dt = 1 never promised to conserve energy.
  static bool newtonian(const World& world) {
    for (const Field& field : world.fields()) {
      const AttractionLaw* law = nullptr;
      if (const auto* a = std::get_if<Attractor>(&field); a != nullptr && a->enabled) law = &a->law;
      if (const auto* m = std::get_if<MutualAttraction>(&field); m != nullptr && m->enabled) {
        law = &m->law;
      }
      if (law != nullptr && !law->custom && law->clamp == DistanceClamp::none) return true;
    }
    return false;
  }
  EnergyWatch watch_;
  bool warn_;
  std::int64_t every_;
  bool fail_;
  bool cheap_;
  std::ostream& lines_;
  std::ostream& err_;
};

}  // namespace

CLI::App* add_run_command(CLI::App& app, RunOptions& options) {
  CLI::App* run = app.add_subcommand(
      "run", "Run a scene headless; print a summary, or write its trajectory with --trajectory");
  add_input_options(*run, options.input);
  CLI::Option* trajectory =
      run->add_option("--trajectory", options.trajectory,
                      "Write the trajectory (frame 0 = after setup, then one frame per step) "
                      "to FILE, '-' for standard output. CSV frame,body,x,y,vx,vy, or JSON. "
                      "Written to a temporary file renamed on success: never left half written. "
                      "At most 50000000 rows, (frames + 1) * bodies")
          ->type_name("FILE");
  run->add_option("--format", options.format,
                  "Trajectory format (default: json for a FILE ending in .json, else csv)")
      ->type_name("csv|json")
      ->needs(trajectory);
  run->add_option("--energy-every", options.energy_every,
                  "Print the total energy and its relative error since the start every K frames "
                  "(to standard error with --trajectory)")
      ->type_name("K")
      ->check(CLI::Range(std::int64_t{1}, max_frames));
  run->add_option("--energy-threshold", options.energy_threshold,
                  "Warn (one line on standard error, naming the frame) the first time the "
                  "relative energy error passes X (default 1e-6); only for scenes that conserve "
                  "energy")
      ->type_name("X")
      ->check(CLI::PositiveNumber);
  run->add_flag("--fail-on-energy", options.fail_on_energy,
                "Exit 1 after the summary when the energy error passed the threshold");
  add_snapshot_options(*run, options.snapshot);
  add_device_option(*run, options.device);  // calder::gpu (devices_command.hpp)
  run->footer(
      "Without --trajectory, prints the scene, frames, bodies, dt, seed, kinetic, potential and "
      "total energy, linear and angular momentum and the state hash.\n"
      "JSON: {\"scene\", \"frames\", \"bodies\", \"dt\", \"seed\", \"columns\": [\"frame\", "
      "\"body\", \"x\", \"y\", \"vx\", \"vy\"], \"rows\": [[frame, body, x, y, vx, vy], ...]}.\n"
      "Numbers are written in the shortest form that reads back to the same double.\n"
      "Exit status: 0 success, 1 the run failed (e.g. a step produced NaN), 2 bad usage or "
      "bad input.\n");
  return run;
}

TrajectoryFormat trajectory_format(const std::optional<std::string>& format,
                                   const std::string& path) {
  if (format) {
    if (*format == "csv") return TrajectoryFormat::csv;
    if (*format == "json") return TrajectoryFormat::json;
    throw InputError("--format: expected csv or json, got '" + *format + "'");
  }
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.ends_with(".json") ? TrajectoryFormat::json : TrajectoryFormat::csv;
}

void check_trajectory_rows(std::int64_t frames, std::size_t bodies) {
  // frames <= 10^7 and bodies <= 10^7: the product fits in 64 bits.
  const auto rows = static_cast<unsigned long long>(frames + 1) * bodies;
  if (rows > static_cast<unsigned long long>(max_trajectory_rows)) {
    throw InputError("--trajectory: (frames + 1) * bodies = " + std::to_string(frames + 1) + " * " +
                     std::to_string(bodies) + " = " + std::to_string(rows) +
                     " rows, over the limit of " + std::to_string(max_trajectory_rows) +
                     " rows (use fewer --frames)");
  }
}

void run_frames(Simulation& simulation, std::int64_t frames, const std::string& source,
                const std::function<void(std::int64_t)>& after_step) {
  while (simulation.frame() < frames) {
    try {
      simulation.step();
    } catch (const Error& e) {
      throw_run_failure(e, source, simulation.frame() + 1);
    }
    if (after_step) after_step(simulation.frame());
  }
}

void run_command(const RunOptions& options, std::ostream& out, std::ostream& err) {
  if (options.trajectory) (void)trajectory_format(options.format, *options.trajectory);
  check_snapshot_options(options.snapshot, options.input.scene);
  const PreparedInput input = prepare_input(options.input);
  check_run_outputs(options, input);
  Simulation simulation = start_simulation(input);
  use_device(options.device, simulation);  // --device gpu: every step on the GPU, or an error
  const std::int64_t frames = input.scene.frames;
  check_world_work(input, simulation,
                   {.once = options.trajectory
                                ? 0.0
                                : static_cast<double>(summary_potential_cost(simulation.world()))});
  if (options.trajectory) check_trajectory_rows(frames, simulation.world().body_count());
  check_bytes_written(options, input, simulation);

  // A terminating signal stops the run at the next frame (exit 128 + signal,
  // the temporaries removed); long runs show their progress on a terminal.
  // The outputs are made only now, every check passed.
  const InterruptGuard interrupt;
  SnapshotOutputs snapshots(options.snapshot, simulation);
  Progress progress(err, "run " + detail::printable(input.scene.name), frames,
                    stderr_is_terminal());
  EnergyMonitor energy(simulation, options, options.trajectory ? err : out, err);
  const auto after_frame = [&](std::int64_t frame) {
    interrupt.check();
    progress.update(frame);
    snapshots.after_frame(simulation);
    energy.after_frame(simulation);
  };

  if (!options.trajectory) {
    run_frames(simulation, frames, input.source, after_frame);
    snapshots.finish(simulation);
    progress.finish();
    print_summary(
        out, simulation, input.effective_seed(), input.source, [&interrupt] { interrupt.check(); },
        &energy.watch());
    energy.finish(input.source);
    return;
  }

  const std::string& path = *options.trajectory;
  const TrajectoryFormat format = trajectory_format(options.format, path);
  OutputFile file(path);
  std::ostream& stream = file.is_stdout() ? out : file.stream();
  if (format == TrajectoryFormat::csv) {
    TrajectoryWriter writer(stream);
    write_run(simulation, input, writer, file, stream, after_frame);
  } else {
    TrajectoryJsonWriter writer(stream, {.scene = simulation.scene().name,
                                         .frames = frames,
                                         .bodies = simulation.world().body_count(),
                                         .dt = simulation.world().dt(),
                                         .seed = input.effective_seed()});
    write_run(simulation, input, writer, file, stream, after_frame);
    writer.finish();
  }
  if (file.is_stdout()) {
    out.flush();
    check_standard_output(out);
  }
  file.commit();
  snapshots.finish(simulation);
  progress.finish();
  energy.finish(input.source);
}

void print_scene_list(std::ostream& out) {
  const auto& scenes = builtin_scenes();
  std::size_t width = 0;
  for (const SceneInfo& s : scenes) width = std::max(width, s.name.size());
  for (const SceneInfo& s : scenes) {
    std::string name = s.name;
    name.resize(width + 2, ' ');
    out << name << s.description << '\n';
  }
}

}  // namespace calder::app
