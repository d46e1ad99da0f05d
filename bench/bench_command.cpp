// SPDX-License-Identifier: MIT
// calder-bench's command: its flags, the sections it runs and the report.
#include "bench_command.hpp"

#include <CLI/CLI.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bench_parts.hpp"
#include "errors.hpp"
#include "output_file.hpp"

namespace calder::app {

using namespace bench;  // NOLINT(google-build-using-namespace): this file runs the parts

void add_bench_flags(CLI::App& bench, BenchOptions& options) {
  bench
      .add_option(
          "--only", options.only,
          "Sections to run, comma-separated: nbody, bulk, barnes-hut, scaling (default: all)")
      ->type_name("LIST");
  bench
      .add_option("--threads", options.threads,
                  "Thread counts of the scaling table, comma-separated (default 1,2; e.g. "
                  "1,2,4,8,16)")
      ->type_name("LIST");
  bench.add_flag("--quick", options.quick,
                 "Tiny sizes and times: a few seconds, rough figures (a smoke test)");
  bench.add_option("--format", options.format, "text (default) or markdown (GitHub tables)")
      ->type_name("FORMAT");
  bench
      .add_option("--output", options.output,
                  "Write the tables to FILE (atomically) instead of standard output")
      ->type_name("FILE");
  bench
      .add_option("--min-time", options.min_time,
                  "Seconds per repetition, in (0, 60] (default 0.5; --quick 0.01)")
      ->type_name("SECONDS");
  bench.footer(
      "The full run takes a few minutes; each figure is the median of several repetitions, "
      "after one warm-up. Progress lines go to standard error when it is a terminal.\n"
      "Exit status: 0 success (whether or not the targets are met), 1 a write failed, 2 bad "
      "usage or an output path that can't be written.\n");
}

namespace {

// The machine lines and the sections, as text or Markdown.
std::string report_text(const std::vector<std::pair<std::string, std::string>>& header,
                        const std::vector<Section>& sections, bool markdown) {
  std::ostringstream report;
  if (markdown) {
    report << "## Machine\n\n";
    for (const auto& [key, value] : header) report << "- " << key << ": " << value << '\n';
  } else {
    report << "calder-bench\n";
    for (const auto& [key, value] : header) {
      report << "  " << key << std::string(10 - std::min<std::size_t>(key.size(), 9), ' ') << value
             << '\n';
    }
  }
  report << '\n';
  for (const Section& section : sections) print_section(report, section, markdown);
  std::string text = report.str();
  while (text.size() >= 2 && text[text.size() - 1] == '\n' && text[text.size() - 2] == '\n') {
    text.pop_back();
  }
  return text;
}

}  // namespace

void bench_command(const BenchOptions& options, std::ostream& out, std::ostream& err) {
  Plan plan = options.quick ? quick_plan() : Plan{};
  if (options.only) parse_only(*options.only, plan);
  if (options.min_time) plan.min_time = parse_min_time(*options.min_time);
  if (options.threads) plan.threads = parse_threads(*options.threads);
  const std::string format = options.format.value_or("text");
  if (format != "text" && format != "markdown") {
    throw InputError("--format: expected text or markdown, got '" + format + "'");
  }
  const bool markdown = format == "markdown";
  // Before minutes of measuring: a path that can't be written fails now.
  std::optional<OutputFile> file;
  if (options.output && *options.output != "-") file.emplace(*options.output);

  auto header = machine(plan);  // the date and the load before we add ours
  const CpuTimes start = cpu_times();
  Runner runner(plan, err);
  Results results;
  std::vector<Section> sections;
  if (plan.nbody) sections.push_back(nbody_section(plan, runner, results));
  if (plan.bulk) sections.push_back(bulk_section(plan, runner, results));
  if (plan.barnes_hut) sections.push_back(barnes_hut_section(plan, runner, results));
  if (plan.scaling) sections.push_back(scaling_section(plan, runner));
  sections.push_back(targets_section(plan, results));
  if (const std::string others = others_share(start, cpu_times()); !others.empty()) {
    header.emplace_back("others", "other processes took " + others +
                                      " of the CPUs during the run (0% for clean figures)");
  }

  std::string text = report_text(header, sections, markdown);
  if (file) {
    file->stream() << text;
    file->commit();
  } else {
    out << text;
  }
}

}  // namespace calder::app
