// SPDX-License-Identifier: MIT
// check_kernel_spills: lint.bulk_kernels_spills. Reads the machine code of
// calder::bulk's kernel objects (objdump -d) and measures how much their
// vector loops spill: in every function whose name contains FUNCTION, the
// innermost loops (a backward jump and its target, containing no other such
// range) that call nothing, and in them the vector registers stored to the
// stack (%rsp or %rbp) against all instructions on vector registers.
//
//   check_kernel_spills OBJDUMP FUNCTION MAX_PERCENT OBJECT...
//
// Exits 1, naming the worst loops, when the stores exceed MAX_PERCENT of the
// vector instructions in any object; 2 on bad arguments or no loop found.
// (The kernels' design keeps a vector's state in a few registers whatever
// the register file, 16 with AVX2: a design that outgrows it spills.)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <regex>
#include <string>
#include <vector>

namespace {

struct Instruction {
  unsigned long address = 0;
  std::string text;
};

struct Function {
  std::string name;
  std::vector<Instruction> code;
};

struct LoopCount {
  std::string where;
  long vector = 0;
  long stores = 0;
};

std::vector<Function> disassemble(const std::string& objdump, const std::string& object) {
  const std::string command = objdump + " -d --no-show-raw-insn '" + object + "'";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    std::cerr << "check_kernel_spills: cannot run " << command << "\n";
    std::exit(2);
  }
  static const std::regex header(R"(^([0-9a-f]+) <(.*)>:$)");
  static const std::regex line(R"(^\s+([0-9a-f]+):\s+(.*)$)");
  std::vector<Function> functions;
  std::string text;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) {
    text.assign(buffer);
    if (!text.empty() && text.back() == '\n') text.pop_back();
    std::smatch m;
    if (std::regex_match(text, m, header)) {
      functions.push_back({m[2].str(), {}});
    } else if (!functions.empty() && std::regex_match(text, m, line)) {
      functions.back().code.push_back({std::stoul(m[1].str(), nullptr, 16), m[2].str()});
    }
  }
  if (pclose(pipe) != 0) {
    std::cerr << "check_kernel_spills: " << command << " failed\n";
    std::exit(2);
  }
  return functions;
}

// The innermost loops of f that call nothing: their vector instructions and
// vector stores to the stack.
std::vector<LoopCount> loops_of(const Function& f) {
  static const std::regex jump(R"(^j[a-z]+\s+([0-9a-f]+)\b)");
  static const std::regex vector(R"(%[xyz]mm[0-9]+)");
  static const std::regex stack_store(R"(%[xyz]mm[0-9]+,(-?0x[0-9a-f]+)?\(%r[sb]p)");
  std::vector<std::pair<unsigned long, unsigned long>> ranges;
  for (const Instruction& i : f.code) {
    std::smatch m;
    if (std::regex_search(i.text, m, jump)) {
      const unsigned long target = std::stoul(m[1].str(), nullptr, 16);
      if (target <= i.address) ranges.emplace_back(target, i.address);
    }
  }
  std::vector<LoopCount> loops;
  for (const auto& [lo, hi] : ranges) {
    const bool innermost = std::none_of(ranges.begin(), ranges.end(), [&](const auto& other) {
      return other != std::make_pair(lo, hi) && lo <= other.first && other.second <= hi;
    });
    if (!innermost) continue;
    LoopCount count;
    bool calls = false;
    for (const Instruction& i : f.code) {
      if (i.address < lo || i.address > hi) continue;
      if (i.text.rfind("call", 0) == 0) calls = true;
      if (std::regex_search(i.text, vector)) ++count.vector;
      if (std::regex_search(i.text, stack_store)) ++count.stores;
    }
    if (calls || count.vector == 0) continue;
    char where[64];
    std::snprintf(where, sizeof where, "%lx-%lx", lo, hi);
    count.where = where;
    loops.push_back(count);
  }
  return loops;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::cerr << "usage: check_kernel_spills OBJDUMP FUNCTION MAX_PERCENT OBJECT...\n";
    return 2;
  }
  const std::string objdump = argv[1];
  const std::string function = argv[2];
  const double max_percent = std::atof(argv[3]);
  int status = 0;
  for (int a = 4; a < argc; ++a) {
    long vector = 0;
    long stores = 0;
    std::vector<LoopCount> all;
    for (const Function& f : disassemble(objdump, argv[a])) {
      if (f.name.find(function) == std::string::npos) continue;
      for (LoopCount& loop : loops_of(f)) {
        vector += loop.vector;
        stores += loop.stores;
        loop.where = f.name + " " + loop.where;
        all.push_back(loop);
      }
    }
    if (vector == 0) {
      std::cerr << "check_kernel_spills: no vector loop in a function '" << function << "' of "
                << argv[a] << "\n";
      return 2;
    }
    const double percent = 100.0 * static_cast<double>(stores) / static_cast<double>(vector);
    std::cout << argv[a] << ": " << all.size() << " vector loops, " << vector
              << " vector instructions, " << stores << " vector stores to the stack (" << percent
              << "%, at most " << max_percent << "%)\n";
    if (percent > max_percent) {
      status = 1;
      std::sort(all.begin(), all.end(),
                [](const LoopCount& x, const LoopCount& y) { return x.stores > y.stores; });
      for (std::size_t k = 0; k < all.size() && k < 5; ++k) {
        std::cout << "  " << all[k].stores << " stores in " << all[k].vector
                  << " vector instructions: " << all[k].where << "\n";
      }
    }
  }
  return status;
}
