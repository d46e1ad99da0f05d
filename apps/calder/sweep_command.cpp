// SPDX-License-Identifier: MIT
#include "sweep_command.hpp"

#include <sys/stat.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <regex>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/scene.hpp"
#include "calder/trajectory.hpp"
#include "calder/world.hpp"
#include "errors.hpp"
#include "output_file.hpp"
#include "output_policy.hpp"
#include "parse.hpp"
#include "progress.hpp"
#include "scene_source.hpp"

#ifdef CALDER_APP_HAS_SCENE_FILE
#include <toml++/toml.h>

#include "calder/scene_file.hpp"
#endif

namespace calder::app {

namespace {

using detail::printable;

// --- records -------------------------------------------------------------------

// The columns of "diagnostics", as calder.Ensemble names them.
const std::vector<std::string> diagnostic_names = {
    "kinetic_energy", "potential_energy", "total_energy",     "momentum_x",
    "momentum_y",     "angular_momentum", "center_of_mass_x", "center_of_mass_y"};
const std::vector<std::string> body_column_names = {"x", "y", "vx", "vy", "mass", "radius"};

struct Records {
  std::vector<std::string> scalars;  // state_hash and diagnostics, in order
  std::vector<std::string> bodies;   // body columns, one row per body
};

void add_once(std::vector<std::string>& list, const std::string& name) {
  if (std::find(list.begin(), list.end(), name) == list.end()) list.push_back(name);
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

Records parse_records(const std::string& text) {
  Records records;
  std::vector<std::string_view> known = {"state_hash", "diagnostics", "bodies"};
  for (const std::string& d : diagnostic_names) known.emplace_back(d);
  for (const std::string& b : body_column_names) known.emplace_back(b);
  for (const std::string& name : split(text, ',')) {
    if (name == "state_hash") {
      add_once(records.scalars, name);
    } else if (name == "diagnostics") {
      for (const std::string& d : diagnostic_names) add_once(records.scalars, d);
    } else if (name == "bodies") {
      for (const std::string& b : body_column_names) add_once(records.bodies, b);
    } else if (std::find(diagnostic_names.begin(), diagnostic_names.end(), name) !=
               diagnostic_names.end()) {
      add_once(records.scalars, name);
    } else if (std::find(body_column_names.begin(), body_column_names.end(), name) !=
               body_column_names.end()) {
      add_once(records.bodies, name);
    } else {
      std::string message = "--record: unknown record '" + printable(name) + "'";
      if (const auto near = detail::closest(name, known)) {
        message += " (did you mean '" + std::string(*near) + "'?)";
      }
      throw InputError(message +
                       "; records are state_hash, diagnostics, bodies or one of their columns");
    }
  }
  if (records.scalars.empty() && records.bodies.empty()) {
    throw InputError("--record: names nothing to record");
  }
  return records;
}

double diagnostic(const std::string& name, const World& world) {
  if (name == "kinetic_energy") return kinetic_energy(world);
  if (name == "potential_energy") return potential_energy(world);
  if (name == "total_energy") return total_energy(world);
  if (name == "momentum_x") return linear_momentum(world).x;
  if (name == "momentum_y") return linear_momentum(world).y;
  if (name == "angular_momentum") return angular_momentum(world);
  if (name == "center_of_mass_x") return center_of_mass(world).x;
  return center_of_mass(world).y;
}

double body_value(const std::string& column, const BodyView& b, std::size_t i) {
  if (column == "x") return b.x[i];
  if (column == "y") return b.y[i];
  if (column == "vx") return b.vx[i];
  if (column == "vy") return b.vy[i];
  if (column == "mass") return b.mass[i];
  return b.radius[i];
}

// --- members ---------------------------------------------------------------------

std::vector<std::uint32_t> parse_seeds(const std::string& text) {
  std::vector<std::uint32_t> seeds;
  for (const std::string& part : split(text, ',')) {
    const std::size_t dash = part.find('-', 1);
    const std::string first = part.substr(0, dash);
    const std::uint32_t low = parse_seed("--seeds", first);
    const std::uint32_t high =
        dash == std::string::npos ? low : parse_seed("--seeds", part.substr(dash + 1));
    if (high < low) {
      throw InputError("--seeds: the range '" + printable(part) + "' ends before it starts");
    }
    if (static_cast<std::int64_t>(high - low) + static_cast<std::int64_t>(seeds.size()) >=
        max_sweep_members) {
      throw InputError("--seeds: more than " + std::to_string(max_sweep_members) + " seeds");
    }
    for (std::uint64_t s = low; s <= high; ++s) seeds.push_back(static_cast<std::uint32_t>(s));
  }
  return seeds;
}

struct Parameter {
  std::string path;
  std::vector<std::string> values;  // as given
};

Parameter parse_set(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw InputError("--set: expected KEY=V1,V2,... (e.g. fields[0].law.G=0.5,1), got '" +
                     printable(text) + "'");
  }
  Parameter parameter{text.substr(0, equals), split(text.substr(equals + 1), ',')};
  for (const std::string& value : parameter.values) {
    if (value.empty()) {
      throw InputError("--set " + printable(parameter.path) + ": an empty value in '" +
                       printable(text) + "'");
    }
  }
  return parameter;
}

struct Member {
  std::size_t index = 0;
  std::uint32_t seed = 0;
  std::vector<std::string> values;  // one per --set, as given
  Scene scene;
  std::vector<std::string> columns;  // the values of the table's columns (not seed's: it has one)
};

#ifdef CALDER_APP_HAS_SCENE_FILE

// A path's steps: keys and list positions ("fields[2].law.G": fields, 2,
// law, G), as calder.scene_edit.parse_path reads them.
struct Step {
  std::string key;
  std::int64_t index = -1;  // >= 0: a position in a list of tables
};

std::vector<Step> parse_path(const std::string& path) {
  static const std::regex segment(R"(([A-Za-z0-9_-]+)((?:\[\d+\])*))");
  std::vector<Step> steps;
  for (const std::string& part : split(path, '.')) {
    std::smatch match;
    if (!std::regex_match(part, match, segment)) {
      throw InputError("--set '" + printable(path) + "': '" + printable(part) +
                       "' is not a key (letters, digits, _ and -) optionally followed by "
                       "[index], as in 'fields[0].law.G'");
    }
    steps.push_back({match[1].str()});
    const std::string indices = match[2].str();
    static const std::regex position(R"(\[(\d+)\])");
    for (std::sregex_iterator it(indices.begin(), indices.end(), position), end; it != end; ++it) {
      const auto i = to_int64((*it)[1].str());
      if (!i || *i > 1'000'000) {
        throw InputError("--set '" + printable(path) + "': index too large");
      }
      steps.push_back({"", *i});
    }
  }
  return steps;
}

std::string spelled(const std::vector<Step>& steps, std::size_t count) {
  std::string text;
  for (std::size_t k = 0; k < count; ++k) {
    if (steps[k].index >= 0) {
      text += "[" + std::to_string(steps[k].index) + "]";
    } else {
      text += (text.empty() ? "" : ".") + steps[k].key;
    }
  }
  return text;
}

// A value as given on the command line, as TOML: an integer, a number, a
// boolean, or else a string (an enumeration's name).
void assign(toml::table& table, const std::string& key, const std::string& text) {
  if (const auto i = to_int64(text)) {
    table.insert_or_assign(key, *i);
  } else if (const auto d = to_double(text)) {
    table.insert_or_assign(key, *d);
  } else if (text == "true" || text == "false") {
    table.insert_or_assign(key, text == "true");
  } else {
    table.insert_or_assign(key, text);
  }
}

// Sets the value at `path` in the scene's TOML; a key that isn't there is
// added for the scene reader to judge (with its "did you mean").
void set_path(toml::table& document, const std::string& path, const std::string& value) {
  const std::vector<Step> steps = parse_path(path);
  toml::node* node = &document;
  const auto where = [&](std::size_t depth) {
    return depth == 0 ? std::string("the scene") : spelled(steps, depth);
  };
  const std::string named = "--set '" + printable(path) + "': ";
  for (std::size_t depth = 0; depth < steps.size(); ++depth) {
    const Step& step = steps[depth];
    const bool last = depth + 1 == steps.size();
    if (step.index >= 0) {
      toml::array* list = node->as_array();
      if (list == nullptr) {
        throw InputError(named + "'" + where(depth) +
                         "' is not a list of tables, so it takes no [index]");
      }
      if (static_cast<std::size_t>(step.index) >= list->size()) {
        throw InputError(named + (list->empty() ? "the scene has no '" + where(depth) + "'"
                                                : "the scene has " + std::to_string(list->size()) +
                                                      " '" + where(depth) + "' (indices 0 to " +
                                                      std::to_string(list->size() - 1) + ")"));
      }
      if (last) {
        throw InputError(named + "a whole table can't be set; name one of its keys");
      }
      node = list->get(static_cast<std::size_t>(step.index));
      continue;
    }
    toml::table* table = node->as_table();
    if (table == nullptr) {
      throw InputError(named + "'" + where(depth) + "' is a " +
                       (node->is_array() ? "list, not a table; pick one with [index]"
                                         : "value, not a table; it has no keys"));
    }
    if (last) {
      assign(*table, step.key, value);
      return;
    }
    if (!table->contains(step.key)) {
      if (steps[depth + 1].index >= 0) {
        std::string known;
        for (const auto& [key, child] : *table) {
          known += (known.empty() ? "'" : ", '") + std::string(key.str()) + "'";
        }
        throw InputError(named + "the scene has no '" + spelled(steps, depth + 1) +
                         "' (its keys here: " + (known.empty() ? "none" : known) + ")");
      }
      table->insert(step.key, toml::table{});
    }
    node = table->get(step.key);
  }
}

// The scene reader's message without its "<scene>:LINE:COLUMN: " (a line of
// text the user never saw).
std::string without_location(const std::string& message) {
  static const std::regex location(R"(^<scene>:\d+:\d+: )");
  return std::regex_replace(message, location, "");
}

std::vector<Member> make_members(const Scene& base, const std::vector<Parameter>& parameters,
                                 const std::vector<std::uint32_t>& seeds, bool seeds_given,
                                 std::int64_t frames) {  // < 0: the scene's
  const toml::table document = toml::parse(to_toml(base));
  std::size_t combinations = 1;
  for (const Parameter& p : parameters) {
    combinations *= p.values.size();
    if (combinations * seeds.size() > static_cast<std::size_t>(max_sweep_members)) {
      throw InputError("--set, --seeds: more than " + std::to_string(max_sweep_members) +
                       " members");
    }
  }
  std::vector<Member> members;
  members.reserve(combinations * seeds.size());
  for (std::size_t c = 0; c < combinations; ++c) {
    std::vector<std::string> values(parameters.size());
    std::size_t rest = c;
    for (std::size_t k = parameters.size(); k-- > 0;) {  // the last changes fastest
      values[k] = parameters[k].values[rest % parameters[k].values.size()];
      rest /= parameters[k].values.size();
    }
    for (const std::uint32_t seed : seeds) {
      toml::table edited = document;
      if (seeds_given) edited.insert_or_assign("seed", static_cast<std::int64_t>(seed));
      std::string described;
      for (std::size_t k = 0; k < parameters.size(); ++k) {
        set_path(edited, parameters[k].path, values[k]);
        described += (k ? ", " : "") + parameters[k].path + "=" + values[k];
      }
      std::ostringstream text;
      text << edited;
      Member member{members.size(), 0, values, {}, {}};
      for (std::size_t k = 0; k < parameters.size(); ++k) {
        if (parameters[k].path != "seed") member.columns.push_back(values[k]);
      }
      try {
        member.scene = parse_scene(text.str(), "<scene>");
        member.scene.validate();
      } catch (const Error& e) {
        throw InputError("--set " + printable(described.empty() ? "(none)" : described) + ": " +
                         without_location(e.what()));
      }
      if (frames >= 0) member.scene.frames = frames;
      member.seed = member.scene.world.seed;
      members.push_back(std::move(member));
    }
  }
  return members;
}

#endif  // CALDER_APP_HAS_SCENE_FILE

// --- the table -------------------------------------------------------------------

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::vector<std::int64_t> recorded_frames(std::int64_t frames, std::optional<std::int64_t> every) {
  std::vector<std::int64_t> wanted;
  if (every) {
    for (std::int64_t f = 0; f <= frames; f += *every) wanted.push_back(f);
  }
  if (wanted.empty() || wanted.back() != frames) wanted.push_back(frames);
  return wanted;
}

// One member's rows of the table (or its error): run where the sweep's
// threads take it, in no particular order; the rows depend only on the member.
struct Outcome {
  std::string rows;
  std::string error;
};

Outcome run_member(const Member& member, const Records& records, std::optional<std::int64_t> every,
                   const std::atomic<bool>& stop) {
  Outcome outcome;
  std::string head = std::to_string(member.index) + "," + std::to_string(member.seed);
  for (const std::string& value : member.columns) head += "," + csv_field(value);
  try {
    Simulation simulation(member.scene);
    simulation.world().set_threads(1);  // the cores go to members
    for (const std::int64_t frame : recorded_frames(member.scene.frames, every)) {
      while (simulation.frame() < frame) {
        if (stop.load(std::memory_order_relaxed)) return outcome;
        try {
          simulation.step();
        } catch (const Error& e) {
          throw RunError("frame " + std::to_string(simulation.frame() + 1) + ": " + e.what());
        }
      }
      const World& world = simulation.world();
      std::string scalars;
      for (const std::string& name : records.scalars) {
        scalars += "," + (name == "state_hash" ? std::to_string(state_hash(world))
                                               : format_number(diagnostic(name, world)));
      }
      const std::string prefix = head + "," + std::to_string(frame);
      if (records.bodies.empty()) {
        outcome.rows += prefix + scalars + "\n";
        continue;
      }
      const BodyView bodies = world.bodies();
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        outcome.rows += prefix + "," + std::to_string(i) + scalars;
        for (const std::string& column : records.bodies) {
          outcome.rows += "," + format_number(body_value(column, bodies, i));
        }
        outcome.rows += "\n";
      }
    }
  } catch (const std::exception& e) {  // this member's failure, reported with it
    outcome.rows.clear();
    outcome.error = one_line(e.what());
  }
  return outcome;
}

bool ends_with_lower(std::string text, std::string_view suffix) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text.ends_with(suffix);
}

}  // namespace

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options) {
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "Run many members of a scene (seeds x parameter values) on the local cores; "
      "write a CSV table");
  sweep->add_option("scene", options.scene, "A built-in scene's name or a scene file")
      ->required()
      ->type_name("SCENE|FILE");
  sweep
      ->add_option("--seeds", options.seeds,
                   "The members' seeds: a range 0-99, a list 1,5,9 or both (0-9,20); default: "
                   "the scene's seed")
      ->type_name("LIST");
  sweep
      ->add_option("--set", options.set,
                   "A parameter path of the scene file and its values, e.g. world.dt=0.5,1 or "
                   "fields[0].law.G=0.5,1,2 (repeatable: every combination runs)")
      ->type_name("KEY=V1,V2");
  sweep->add_option("--frames", options.frames, "Frames per member (default: the scene's)")
      ->type_name("N");
  sweep
      ->add_option("--every", options.every,
                   "Record frame 0, every K-th frame and the last (default: the last only)")
      ->type_name("K");
  sweep
      ->add_option("--record", options.record,
                   "What to record: state_hash, diagnostics (kinetic_energy, potential_energy, "
                   "total_energy, momentum_x, momentum_y, angular_momentum, center_of_mass_x, "
                   "center_of_mass_y), bodies (x, y, vx, vy, mass, radius: a row per body), "
                   "or any of those columns; default state_hash,diagnostics")
      ->type_name("LIST");
  sweep->add_option("--jobs", options.jobs, "Members run at once (default: the cores)")
      ->type_name("N");
  sweep
      ->add_option("--output", options.output,
                   "The table: FILE.csv ('-' for standard output), written whole or not at all")
      ->required()
      ->type_name("FILE");
  sweep->footer(
      "Columns: member, seed, each --set key, frame, [body], the records; one row per member "
      "and recorded frame (and body), sorted by member. The members and their numbers are "
      "calder.Ensemble's in Python for the same scene, seeds and values. state_hash is "
      "decimal; numbers are in the shortest form that reads back to the same double.\n"
      "Exit status: 0 success, 1 a member failed (reported, the others written), 2 bad usage "
      "or bad input (before any member runs).\n");
  return sweep;
}

namespace {

// The flags, checked: everything but the scene.
struct SweepPlan {
  Records records;
  std::int64_t frames = -1;  // < 0: the scene's
  std::optional<std::int64_t> every;
  std::size_t jobs = 1;
  std::vector<Parameter> parameters;
  std::vector<std::uint32_t> seeds;
};

void check_output_name(const std::string& output) {
  if (ends_with_lower(output, ".parquet")) {
    throw InputError("--output " + printable(output) +
                     ": this calder writes no parquet (Debian 12 packages no parquet writer: "
                     "no pyarrow, no Arrow for C++); write .csv");
  }
  if (output != "-" && !ends_with_lower(output, ".csv")) {
    throw InputError("--output " + printable(output) + ": expected a FILE.csv or '-'");
  }
}

std::vector<Parameter> parse_parameters(const SweepOptions& options) {
  std::vector<Parameter> parameters;
  for (const std::string& text : options.set) {
    Parameter parameter = parse_set(text);
    if (parameter.path == "seed" && options.seeds) {
      throw InputError("--set seed: give --seeds or --set seed=..., not both");
    }
    for (const Parameter& other : parameters) {
      if (other.path == parameter.path) {
        throw InputError("--set " + printable(parameter.path) + ": given twice");
      }
    }
    parameters.push_back(std::move(parameter));
  }
  return parameters;
}

SweepPlan parse_plan(const SweepOptions& options) {
  check_output_name(options.output);
  SweepPlan plan;
  plan.records = parse_records(options.record);
  if (options.frames) plan.frames = parse_frames("--frames", *options.frames);
  if (options.every) {
    plan.every = parse_frames("--every", *options.every);
    if (*plan.every < 1) throw InputError("--every: expected an integer >= 1, got '0'");
  }
  plan.jobs = std::max(1U, std::thread::hardware_concurrency());
  if (options.jobs) {
    const auto n = to_int64(*options.jobs);
    if (!n || *n < 1 || *n > 4096) {
      throw InputError("--jobs: expected an integer from 1 to 4096, got '" +
                       printable(*options.jobs) + "'");
    }
    plan.jobs = static_cast<std::size_t>(*n);
  }
  plan.parameters = parse_parameters(options);
  plan.seeds = options.seeds ? parse_seeds(*options.seeds) : std::vector<std::uint32_t>{0};
  return plan;
}

std::vector<Member> sweep_members(const SweepOptions& options, const SweepPlan& plan,
                                  const Scene& base) {
#ifdef CALDER_APP_HAS_SCENE_FILE
  return make_members(base, plan.parameters, plan.seeds, options.seeds.has_value(), plan.frames);
#else
  if (!plan.parameters.empty()) {
    throw InputError("--set: this calder was built without scene files (calder::scene_file)");
  }
  std::vector<Member> members;
  for (const std::uint32_t seed : plan.seeds) {
    Member member{members.size(), seed, {}, base, {}};
    if (options.seeds) member.scene.world.seed = seed;
    member.seed = member.scene.world.seed;
    if (plan.frames >= 0) member.scene.frames = plan.frames;
    members.push_back(std::move(member));
  }
  return members;
#endif
}

// Runs the members on plan.jobs threads, each taking the next member; the
// outcomes come back in member order. A terminating signal stops them all
// at their next frame (Interrupted, exit 128 + signal).
std::vector<Outcome> run_members(const std::vector<Member>& members, const SweepPlan& plan,
                                 const std::string& label, std::ostream& err) {
  std::vector<Outcome> outcomes(members.size());
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  std::atomic<bool> stop{false};
  const auto work = [&] {
    for (std::size_t i = next++; i < members.size() && !stop; i = next++) {
      outcomes[i] = run_member(members[i], plan.records, plan.every, stop);
      ++done;
    }
  };
  const InterruptGuard interrupt;
  Progress progress(err, label, static_cast<std::int64_t>(members.size()), stderr_is_terminal());
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < std::min(plan.jobs, members.size()); ++t) threads.emplace_back(work);
  try {
    while (done.load() < members.size()) {
      interrupt.check();
      progress.update(static_cast<std::int64_t>(done.load()));
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  } catch (...) {
    stop = true;
    for (std::thread& t : threads) t.join();
    throw;
  }
  for (std::thread& t : threads) t.join();
  progress.finish();
  return outcomes;
}

std::string table_header(const SweepPlan& plan) {
  std::string header = "member,seed";
  for (const Parameter& p : plan.parameters) {
    if (p.path != "seed") header += "," + csv_field(p.path);  // the seed column holds it
  }
  header += plan.records.bodies.empty() ? ",frame" : ",frame,body";
  for (const std::string& name : plan.records.scalars) header += "," + name;
  for (const std::string& name : plan.records.bodies) header += "," + name;
  return header;
}

// Writes the rows of the members that ran, reports each that failed on
// `err`; returns how many failed.
std::size_t write_table(std::ostream& stream, OutputFile& file, const SweepPlan& plan,
                        const std::vector<Member>& members, const std::vector<Outcome>& outcomes,
                        std::ostream& err) {
  stream << table_header(plan) << '\n';
  std::size_t failed = 0;
  for (std::size_t i = 0; i < members.size(); ++i) {
    if (outcomes[i].error.empty()) {
      stream << outcomes[i].rows;
      file.check_stream(stream);
      continue;
    }
    ++failed;
    std::string described;
    for (std::size_t k = 0; k < plan.parameters.size(); ++k) {
      described += plan.parameters[k].path + "=" + members[i].values[k] + ", ";
    }
    err << "calder: sweep: member " << i << " (" << described << "seed " << members[i].seed
        << ") failed: " << outcomes[i].error << '\n';
  }
  return failed;
}

}  // namespace

void sweep_command(const SweepOptions& options, std::ostream& out, std::ostream& err) {
  const SweepPlan plan = parse_plan(options);
  const Scene base = load_scene_argument(options.scene);
  const std::vector<Member> members = sweep_members(options, plan, base);

  std::vector<NamedPath> inputs;
  struct stat info {};
  if (::stat(options.scene.c_str(), &info) == 0) {
    inputs.push_back({"the scene file", options.scene});
  }
  check_outputs(inputs, {{"--output", options.output}});
  OutputFile file(options.output);
  std::ostream& stream = file.is_stdout() ? out : file.stream();

  const std::vector<Outcome> outcomes =
      run_members(members, plan, "sweep " + printable(base.name), err);
  const std::size_t failed = write_table(stream, file, plan, members, outcomes, err);
  if (file.is_stdout()) {
    out.flush();
    if (!out) throw RunError("standard output: write failed");
  }
  file.commit();
  if (failed > 0) {
    throw RunError("sweep: " + std::to_string(failed) + " of " + std::to_string(members.size()) +
                   " members failed (each reported above); the others are in " +
                   (file.is_stdout() ? std::string("standard output") : options.output));
  }
}

}  // namespace calder::app
