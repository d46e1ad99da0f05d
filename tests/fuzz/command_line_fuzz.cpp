// SPDX-License-Identifier: MIT
// libFuzzer targets for the command line: calder_fuzz_command_line takes
// `calder list`, `run` and `render`; calder_fuzz_window (built with
// CALDER_FUZZ_WINDOW) takes `calder window`, on SDL's dummy video driver.
// The input is the arguments after the verb, separated by NUL bytes; for the
// first target the first byte picks the verb. calder::app::main must return
// 0, 1 or 2 with one line on stderr, never crash.
//
// What an input may do is fenced in: it runs in a private folder, '/' in an
// argument becomes '_' (no file outside that folder is named), and runs are
// capped at a few frames so one input stays quick. The window runs 0 frames:
// it opens, draws once and closes (--screenshot, --print-state), since its
// loop is paced in real time (1/60 s a frame). `bench` is left out: it is a
// timed measurement.
// Run it with -timeout=0: libFuzzer's watchdog is SIGALRM, which calder takes,
// like every terminating signal, as the order to stop (from any of its threads).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "cli.hpp"

namespace {

// Most inputs write nothing. The folder's modification time is set to 0
// after each clean-up; creating, renaming or removing an entry sets it to the
// current time. So one stat a run tells whether there is anything to remove.
bool folder_changed() {
  struct stat info {};
  return ::stat(".", &info) != 0 || info.st_mtim.tv_sec != 0 || info.st_mtim.tv_nsec != 0;
}

void clean_folder() {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(".", ec)) {
    std::filesystem::remove_all(entry.path(), ec);
  }
  const std::array<timespec, 2> epoch{};  // access and modification time 0
  ::utimensat(AT_FDCWD, ".", epoch.data(), 0);
}

bool in_private_folder() {
  static const bool done = [] {
    std::string dir = (std::filesystem::temp_directory_path() / "calder-fuzz-XXXXXX").string();
    if (::mkdtemp(dir.data()) == nullptr) return false;
    std::filesystem::current_path(dir);
    clean_folder();
    return true;
  }();
  return done;
}

// What keeps one run quick: --frames and --every of the input stay when their
// value is one character (at most 9 frames; the window's --frames is the
// harness's), the canvas's size (--size, --scale) is the harness's. False:
// skip the input. frames_given: the input sets --frames itself.
bool within_caps(const std::vector<std::string>& args, bool& frames_given) {
  const bool window = args[1] == "window";
  for (std::size_t i = 2; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg.rfind("--size", 0) == 0 || arg.rfind("--scale", 0) == 0) return false;
    for (const std::string_view flag :
         {std::string_view("--frames"), std::string_view("--every")}) {
      if (arg.rfind(flag, 0) != 0) continue;
      std::string_view value;
      if (arg.size() == flag.size()) {
        if (i + 1 < args.size()) value = args[i + 1];
      } else if (arg[flag.size()] == '=') {
        value = std::string_view(arg).substr(flag.size() + 1);
      } else {
        continue;  // another word, an unknown flag
      }
      if (value.size() > 1) return false;
      if (flag == "--frames") {
        if (window) return false;
        frames_given = true;
      }
    }
  }
  return true;
}

}  // namespace

#ifdef CALDER_FUZZ_WINDOW
// No display here: the dummy driver, which `calder window` uses when asked by
// SDL_VIDEODRIVER.
extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  ::setenv("SDL_VIDEODRIVER", "dummy", 1);
  return 0;
}
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0 || !in_private_folder()) return 0;
#ifdef CALDER_FUZZ_WINDOW
  std::vector<std::string> args = {"calder", "window"};
  const std::size_t first = 0;
#else
  static constexpr std::array<const char*, 3> kVerbs = {"list", "run", "render"};
  std::vector<std::string> args = {"calder", kVerbs[data[0] % kVerbs.size()]};
  const std::size_t first = 1;
#endif
  std::string arg;
  for (std::size_t i = first; i <= size; ++i) {
    if (i == size || data[i] == 0) {
      args.push_back(arg);
      arg.clear();
    } else {
      arg += data[i] == '/' ? '_' : static_cast<char>(data[i]);
    }
  }
  if (args.size() > 24) return 0;
  bool frames_given = false;
  if (!within_caps(args, frames_given)) return 0;
  if (args[1] == "window") {
    args.push_back("--frames");
    args.push_back("0");
  } else if (args[1] != "list" && !frames_given) {
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
  // Nothing of one input stays for the next (PNG folders, trajectories); most
  // inputs write nothing, and then the folder is left as it is.
  if (folder_changed()) clean_folder();
  if (status != 0 && status != 1 && status != 2) std::abort();
  if (status != 0) {
    std::string message = err.str();
    // The window's banner of keys, printed once it opens, before the error.
    if (message.rfind("calder window ", 0) == 0) message.erase(0, message.find('\n') + 1);
    // One line, "calder: ...".
    if (message.rfind("calder: ", 0) != 0 || message.find('\n') != message.size() - 1) {
      std::abort();
    }
  }
  return 0;
}
