// SPDX-License-Identifier: MIT
// libFuzzer target: the command line of `calder list`, `run` and `render`.
// The input is the arguments after the verb, separated by NUL bytes; the
// first byte picks the verb. calder::app::main must return 0, 1 or 2 with
// one line on stderr, never crash.
//
// What an input may do is fenced in: it runs in a private folder, '/' in an
// argument becomes '_' (no file outside that folder is named), and runs are
// capped at a few frames so one input stays quick. `window` and `bench` are
// left out: the first needs a display, the second is a timed measurement.
// Run it with -timeout=0: libFuzzer's watchdog is SIGALRM, which calder takes,
// like every terminating signal, as the order to stop (from any of its threads).
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "cli.hpp"

namespace {

bool in_private_folder() {
  static const bool done = [] {
    std::string dir = (std::filesystem::temp_directory_path() / "calder-fuzz-XXXXXX").string();
    if (::mkdtemp(dir.data()) == nullptr) return false;
    std::filesystem::current_path(dir);
    return true;
  }();
  return done;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0 || !in_private_folder()) return 0;
  static constexpr std::array<const char*, 3> kVerbs = {"list", "run", "render"};
  std::vector<std::string> args = {"calder", kVerbs[data[0] % kVerbs.size()]};
  std::string arg;
  for (std::size_t i = 1; i <= size; ++i) {
    if (i == size || data[i] == 0) {
      args.push_back(arg);
      arg.clear();
    } else {
      arg += data[i] == '/' ? '_' : static_cast<char>(data[i]);
    }
  }
  if (args.size() > 24) return 0;
  bool frames_given = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i].rfind("--frames", 0) == 0 || args[i].rfind("--every", 0) == 0 ||
        args[i].rfind("--size", 0) == 0 || args[i].rfind("--scale", 0) == 0) {
      frames_given = true;
    }
  }
  if (frames_given) return 0;  // the caps below stand; the flags' parsing has unit tests
  if (args[1] != "list") {
    args.push_back("--frames");
    args.push_back("3");
  }
  if (args[1] == "render") {
    args.push_back("--size");
    args.push_back("64x48");
  }
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  std::ostringstream out;
  std::ostringstream err;
  const int status = calder::app::main(static_cast<int>(argv.size()), argv.data(), out, err);
  // Nothing of one input stays for the next (PNG folders, trajectories).
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(".", ec)) {
    std::filesystem::remove_all(entry.path(), ec);
  }
  if (status != 0 && status != 1 && status != 2) std::abort();
  if (status != 0) {
    const std::string message = err.str();
    // One line, "calder: ...".
    if (message.rfind("calder: ", 0) != 0 || message.find('\n') != message.size() - 1) {
      std::abort();
    }
  }
  return 0;
}
