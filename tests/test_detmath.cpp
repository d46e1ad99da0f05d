// SPDX-License-Identifier: MIT
// calder::math against V8's Math, bit for bit: tests/data/detmath_v8.txt holds
// what Node's Math.sin, cos, atan2, log and pow give (written by
// scripts/detmath-vectors, whose comment describes the format): digests of
// the results on hundreds of thousands of drawn arguments, which this test
// draws again, and single hard cases (special values, the algorithms'
// thresholds, arguments next to multiples of pi/2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "calder/detmath.hpp"

namespace {

using u64 = std::uint64_t;

u64 bits_of(double x) {
  u64 u = 0;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
double from_bits(u64 u) {
  double x = 0.0;
  std::memcpy(&x, &u, sizeof x);
  return x;
}
// JavaScript has one NaN; the file writes it as 0x7ff8000000000000.
u64 canonical(double x) { return x != x ? 0x7ff8000000000000ULL : bits_of(x); }

std::string hex(u64 u) {
  std::ostringstream out;
  out << std::hex;
  out.width(16);
  out.fill('0');
  out << u;
  return out.str();
}

// splitmix64 (Steele, Lea and Flood 2014), as the script has it.
class SplitMix {
 public:
  explicit SplitMix(u64 seed) : state_(seed) {}
  u64 next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    u64 z = state_;
    z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31U);
  }

 private:
  u64 state_;
};

std::vector<std::string> split(const std::string& text, char by) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, by)) parts.push_back(part);
  return parts;
}

// An argument spec of the file (e:LO:HI:S, pio2:N:U:S, one:SPAN, int:LO:HI),
// parsed once.
struct Spec {
  std::string kind;
  std::int64_t a = 0;
  std::int64_t b = 0;
  bool random_sign = false;
};
Spec parse_spec(const std::string& text) {
  const std::vector<std::string> p = split(text, ':');
  Spec spec{p.at(0)};
  spec.a = std::stoll(p.at(1));
  if (p.size() > 2) spec.b = std::stoll(p.at(2));
  spec.random_sign = p.size() > 3 && p[3] == "s";
  return spec;
}

// One argument drawn by a spec, the way the script draws it.
double draw(const Spec& spec, SplitMix& rng) {
  if (spec.kind == "e") {
    const u64 r1 = rng.next();
    const u64 r2 = rng.next();
    const auto lo = static_cast<u64>(spec.a);
    const u64 exponent = lo + r2 % (static_cast<u64>(spec.b) - lo + 1);
    const u64 sign = spec.random_sign ? r1 >> 63U : 0;
    return from_bits((sign << 63U) | (exponent << 52U) | (r1 & ((u64{1} << 52U) - 1)));
  }
  if (spec.kind == "pio2") {
    const u64 r1 = rng.next();
    const u64 r2 = rng.next();
    const u64 n = 1 + r1 % static_cast<u64>(spec.a);
    const std::int64_t k =
        static_cast<std::int64_t>(r2 % static_cast<u64>(2 * spec.b + 1)) - spec.b;
    const double x =
        from_bits(bits_of(static_cast<double>(n) * (3.141592653589793 / 2)) + static_cast<u64>(k));
    return spec.random_sign && (r2 >> 63U) == 1 ? -x : x;
  }
  if (spec.kind == "one") {
    const auto span = static_cast<u64>(spec.a);
    return from_bits(bits_of(1.0) + rng.next() % (2 * span + 1) - span);
  }
  if (spec.kind == "int") {
    const u64 range = static_cast<u64>(spec.b - spec.a + 1);
    return static_cast<double>(spec.a + static_cast<std::int64_t>(rng.next() % range));
  }
  ADD_FAILURE() << "unknown argument spec " << spec.kind;
  return 0.0;
}
double draw(const std::string& spec, SplitMix& rng) { return draw(parse_spec(spec), rng); }

using Function = double (*)(const double*);
Function function_named(const std::string& name) {
  if (name == "sin") return [](const double* a) { return calder::math::sin(a[0]); };
  if (name == "cos") return [](const double* a) { return calder::math::cos(a[0]); };
  if (name == "log") return [](const double* a) { return calder::math::log(a[0]); };
  if (name == "atan2") return [](const double* a) { return calder::math::atan2(a[0], a[1]); };
  if (name == "pow") return [](const double* a) { return calder::math::pow(a[0], a[1]); };
  ADD_FAILURE() << "unknown function " << name;
  return [](const double*) { return 0.0; };
}

std::vector<std::vector<std::string>> vector_lines(const std::string& kind) {
  std::ifstream in(std::string(CALDER_SOURCE_DIR) + "/tests/data/detmath_v8.txt");
  EXPECT_TRUE(in.good()) << "tests/data/detmath_v8.txt is missing";
  std::vector<std::vector<std::string>> lines;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> words = split(line, ' ');
    if (!words.empty() && words[0] == kind) lines.push_back(words);
  }
  return lines;
}

// Every drawn class: the digest of calder::math's results equals V8's.
TEST(DetMath, MatchesV8OnDrawnArguments) {
  long total = 0;
  std::vector<std::string> functions;
  for (const auto& w : vector_lines("random")) {
    ASSERT_GE(w.size(), 7U);
    const std::string& function = w[1];
    const long count = std::stol(w[3]);
    SplitMix rng(std::stoull(w[4]));
    std::vector<Spec> specs;
    for (auto s = w.begin() + 5; s != w.end() - 1; ++s) specs.push_back(parse_spec(*s));
    ASSERT_LE(specs.size(), 2U);
    const Function f = function_named(function);
    u64 digest = 0xcbf29ce484222325ULL;
    double args[2] = {};
    for (long i = 0; i < count; ++i) {
      for (std::size_t a = 0; a < specs.size(); ++a) args[a] = draw(specs[a], rng);
      digest = (digest ^ canonical(f(args))) * 0x100000001b3ULL;
    }
    EXPECT_EQ(hex(digest), w.back()) << function << " on " << count << " arguments of class "
                                     << w[2] << " differs from V8 in some result";
    total += count;
    functions.push_back(function);
  }
  // The file is whole: every function, half a million arguments and more.
  for (const char* f : {"sin", "cos", "atan2", "log", "pow"}) {
    EXPECT_NE(std::find(functions.begin(), functions.end(), f), functions.end()) << f;
  }
  EXPECT_GE(total, 500000);
}

// Every hard case, one by one, with the argument and both results on failure.
TEST(DetMath, MatchesV8OnHardCases) {
  int checked = 0;
  int failed = 0;
  for (const auto& w : vector_lines("case")) {
    ASSERT_GE(w.size(), 4U);
    std::vector<double> args;
    for (std::size_t i = 2; i + 1 < w.size(); ++i)
      args.push_back(from_bits(std::stoull(w[i], nullptr, 16)));
    const std::string got = hex(canonical(function_named(w[1])(args.data())));
    ++checked;
    if (got != w.back() && ++failed <= 20) {
      ADD_FAILURE() << w[1] << "(" << w[2] << (w.size() == 5 ? ", " + w[3] : "") << ") = " << got
                    << ", V8 gives " << w.back();
    }
  }
  EXPECT_EQ(failed, 0) << "of " << checked << " hard cases";
  EXPECT_GE(checked, 5000);
}

// The properties a scene relies on, independently of V8: exact values, the
// identities of the special cases, and agreement with the C library to 1 ulp.
TEST(DetMath, SpecialValuesAndAccuracy) {
  EXPECT_EQ(calder::math::sin(0.0), 0.0);
  EXPECT_TRUE(std::signbit(calder::math::sin(-0.0)));
  EXPECT_EQ(calder::math::cos(0.0), 1.0);
  EXPECT_EQ(calder::math::log(1.0), 0.0);
  EXPECT_EQ(calder::math::pow(2.0, 10.0), 1024.0);
  EXPECT_EQ(calder::math::pow(3.0, -2.0), 1.0 / 9.0);
  EXPECT_EQ(calder::math::pow(-2.0, 3.0), -8.0);
  EXPECT_TRUE(std::isnan(calder::math::pow(1.0, INFINITY)));  // JavaScript's, not C's 1
  EXPECT_TRUE(std::isnan(calder::math::pow(-8.0, 1.0 / 3.0)));
  EXPECT_EQ(calder::math::atan2(0.0, -0.0), 3.141592653589793);
  EXPECT_EQ(calder::math::atan2(1.0, 1.0), 3.141592653589793 / 4);
  SplitMix rng(7);
  for (int i = 0; i < 20000; ++i) {
    const double x = draw("e:1013:1030:s", rng);
    const double y = draw("e:1013:1026:s", rng);
    const double ax = std::fabs(x);
    EXPECT_NEAR(calder::math::sin(x), std::sin(x), 4.5e-16) << x;
    EXPECT_NEAR(calder::math::cos(x), std::cos(x), 4.5e-16) << x;
    EXPECT_NEAR(calder::math::atan2(y, x), std::atan2(y, x), 9e-16) << y << ", " << x;
    EXPECT_NEAR(calder::math::log(ax), std::log(ax), 4.5e-16 * std::fabs(std::log(ax)) + 1e-300)
        << x;
    const double p = std::pow(ax, y);
    EXPECT_NEAR(calder::math::pow(ax, y), p, 4.5e-16 * p) << ax << "^" << y;
  }
}

}  // namespace
