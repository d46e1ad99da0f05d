// SPDX-License-Identifier: MIT
// calder-bench: the machine a run measured (/proc, the compiler, the date).
#include <sys/resource.h>
#include <unistd.h>
#include "bench_parts.hpp"

#include <ctime>
#include <fstream>
#include <thread>

#ifndef CALDER_BUILD_TYPE
#define CALDER_BUILD_TYPE "unknown"
#endif

namespace calder::app::bench {

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon == std::string::npos) break;
      std::string model = line.substr(colon + 1);
      model.erase(0, model.find_first_not_of(" \t"));
      return model;
    }
  }
  return "unknown CPU";
}

std::string load_average() {
  std::ifstream loadavg("/proc/loadavg");
  std::string first;
  if (loadavg >> first) return first;
  return "unknown";
}

// The CPU time of the whole machine (/proc/stat) and of this process, so
// that a run can say how much other processes took: they drag the 2-thread
// rows down.

CpuTimes cpu_times() {
  CpuTimes times;
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) {
    times.own = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  }
  std::ifstream stat("/proc/stat");
  std::string name;
  if (!(stat >> name) || name != "cpu") return times;
  std::vector<double> ticks;  // user nice system idle iowait irq softirq steal
  double value = 0.0;
  while (ticks.size() < 8 && stat >> value) ticks.push_back(value);
  const long hz = sysconf(_SC_CLK_TCK);
  if (ticks.size() < 8 || hz <= 0) return times;
  double total = 0.0;
  for (const double t : ticks) total += t;
  times.machine_total = total / static_cast<double>(hz);
  times.machine_busy = (total - ticks[3] - ticks[4]) / static_cast<double>(hz);
  return times;
}

// The share of all CPUs that other processes used between two samples, e.g. "3%".
std::string others_share(const CpuTimes& before, const CpuTimes& after) {
  if (before.machine_busy < 0.0 || after.machine_busy < 0.0) return "";
  const double total = after.machine_total - before.machine_total;
  if (total <= 0.0) return "";
  const double others = (after.machine_busy - before.machine_busy) - (after.own - before.own);
  return printf_text("%.0f", std::max(0.0, 100.0 * others / total)) + "%";
}

// How busy the CPUs are over the next `seconds`, e.g. "2% busy over 0.5 s".
std::string busy_cpus(double seconds) {
  const CpuTimes before = cpu_times();
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  const std::string share = others_share(before, cpu_times());
  if (share.empty()) return "";
  return share + " busy over " + printf_text("%g", seconds) + " s";
}

std::string compiler() {
#if defined(__clang__)
  return std::string("Clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("GCC ") + __VERSION__;
#else
  return "unknown compiler";
#endif
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M UTC", &tm);
  return buffer;
}

// "the scaling table ran 1, 2, 4 threads" (or "1 and 2 threads per row").
std::string thread_list(const Plan& plan) {
  if (!plan.scaling) return "rows ran 1 and 2 threads";
  std::string text = "the scaling table ran ";
  for (std::size_t k = 0; k < plan.threads.size(); ++k) {
    text += (k == 0 ? "" : ", ") + std::to_string(plan.threads[k]);
  }
  return text + " thread(s), the other tables 1 and 2";
}

std::vector<std::pair<std::string, std::string>> machine(const Plan& plan) {
  std::string kernels =
      std::string("n-body ") + nb::kernel_name() + ", calder::bulk " + bulk::kernel_name();
  if (const char* forced = std::getenv("CALDER_KERNELS")) {
    kernels += std::string(" (CALDER_KERNELS=") + forced + ")";
  }
  const std::string busy = busy_cpus(plan.quick ? 0.1 : 0.5);
  std::string build = CALDER_BUILD_TYPE;
#if defined(CALDER_BENCH_PORTABLE)
  build += ", CALDER_PORTABLE=ON";
#endif
  return {
      {"CPU",
       cpu_model() + ", " + std::to_string(std::thread::hardware_concurrency()) + " logical cores"},
      {"kernels", kernels},
      {"threads", "OpenMP max threads " + std::to_string(nb::max_threads()) + " (n-body), " +
                      std::to_string(bulk::max_threads()) + " (calder::bulk); " +
                      thread_list(plan) + " on " +
                      std::to_string(std::thread::hardware_concurrency()) + " logical cores"},
      {"compiler", compiler() + ", build type " + build},
      {"date", utc_now() + "; at the start: " + (busy.empty() ? "" : "CPUs " + busy + ", ") +
                   "load average " + load_average()},
      {"timing", "median of " + std::to_string(plan.repetitions) + " repetitions of at least " +
                     printf_text("%g", plan.min_time) + " s each, after one warm-up; wall clock" +
                     (plan.quick ? " (--quick: tiny sizes, rough figures)" : "")},
  };
}

}  // namespace calder::app::bench
