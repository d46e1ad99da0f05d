// bench_nbody: mutual attraction of N bodies (calder/nbody.hpp), in pair
// interactions per second (N^2 per evaluation: self pairs included, as the
// kernels compute them) and Barnes-Hut evaluations per second.
//
//   Direct/N/precision/threads/law    direct_accelerations; precision 64 or
//                                     32, law 0 = Plummer (eps 0.5), 1 = the
//                                     book's clamp [5, 25]
//   Learner/N                         the book's example 2.9 written plainly in
//                                     C++ (Mover objects, a heap vector per
//                                     force), one thread, the book's clamp
//   FmaPeak/bits/threads              this CPU's FMA throughput: 12 independent
//                                     chains of bits-wide vector FMAs per
//                                     thread, flops/s (an FMA is 2 flops); the
//                                     floor_pairs/s counters divide it by the
//                                     flops of one interaction of each kernel
//   BarnesHut/N/precision/threads/theta100
//                                     one evaluation at theta 0.5 (and 0.45 at
//                                     N = 10^6; leaf 16, group 128) on a
//                                     uniform disk, steps/s, with the RMS and
//                                     max relative error against the direct
//                                     sum (on a sample of 256 bodies for
//                                     N > 10^4)
//   BarnesHutError/theta*100/clusters the error table at N = 10^4, threads 2
//
// Every rate is wall-clock (UseRealTime): threads count. The context block
// names the kernels (calder::nbody::kernel_name()).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "calder/nbody.hpp"

namespace {

namespace nb = calder::nbody;

struct System {
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> m;
};

double uniform(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

// N bodies uniform in a disk of radius 50 * sqrt(N / 1000) (the density of
// 1000 bodies in radius 50), masses in [0.5, 1.5).
System disk(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  const double r = 50.0 * std::sqrt(static_cast<double>(n) / 1000.0);
  System s;
  s.x.reserve(n);
  s.y.reserve(n);
  s.m.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double radius = r * std::sqrt(uniform(g));
    const double angle = 6.283185307179586 * uniform(g);
    s.x.push_back(radius * std::cos(angle));
    s.y.push_back(radius * std::sin(angle));
    s.m.push_back(0.5 + uniform(g));
  }
  return s;
}

// N bodies in 8 Plummer-like clumps of scale 1 to 5 spread over 200 x 200.
System clusters(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  constexpr std::size_t kClumps = 8;
  double cx[kClumps];
  double cy[kClumps];
  double a[kClumps];
  for (std::size_t c = 0; c < kClumps; ++c) {
    cx[c] = 200.0 * uniform(g) - 100.0;
    cy[c] = 200.0 * uniform(g) - 100.0;
    a[c] = 1.0 + 4.0 * uniform(g);
  }
  System s;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c = i % kClumps;
    const double q = std::min(uniform(g), 0.9999);
    const double radius = a[c] * std::sqrt(q / (1.0 - q));
    const double angle = 6.283185307179586 * uniform(g);
    s.x.push_back(cx[c] + radius * std::cos(angle));
    s.y.push_back(cy[c] + radius * std::sin(angle));
    s.m.push_back(0.5 + uniform(g));
  }
  return s;
}

const System& cached_disk(std::size_t n) {
  static std::map<std::size_t, System> systems;
  auto it = systems.find(n);
  if (it == systems.end()) it = systems.emplace(n, disk(n, 42)).first;
  return it->second;
}

// Softening: half the mean spacing of the disks above (sqrt(pi) 50 / sqrt(1000) / 2).
constexpr double kSoftening = 1.4;

nb::Options options_for(std::int64_t precision, std::int64_t threads, std::int64_t law) {
  nb::Options o;
  o.precision = precision == 32 ? nb::Precision::float32 : nb::Precision::float64;
  o.threads = static_cast<int>(threads);
  if (law == 1) {
    o.law = nb::Law::clamp_distance;
    o.min_distance = 5.0;
    o.max_distance = 25.0;
  } else {
    o.softening = kSoftening;
  }
  return o;
}

// ------------------------------------------------------------------ direct ---

void Direct(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const System& s = cached_disk(n);
  const nb::Options o = options_for(state.range(1), state.range(2), state.range(3));
  std::vector<double> ax(n);
  std::vector<double> ay(n);
  for (auto _ : state) {
    nb::direct_accelerations(s.x, s.y, s.m, ax, ay, o);
    benchmark::DoNotOptimize(ax.data());
    benchmark::ClobberMemory();
  }
  const double pairs = static_cast<double>(n) * static_cast<double>(n);
  state.counters["pairs/s"] = benchmark::Counter(pairs * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(Direct)
    ->ArgNames({"N", "precision", "threads", "law"})
    ->ArgsProduct({{1000, 4000, 16000}, {64, 32}, {1, 2}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// ----------------------------------------------------------------- learner ---

// The book's example 2.9 as a learner ports it from p5.js to C++: a Vector
// class with p5.Vector's methods, the static ones (p5.Vector.sub,
// p5.Vector.div) returning a new vector on the heap, and Mover objects
// holding vectors. attract() and applyForce() are the book's, line for line.
// Each class would live in its own .cpp (as each lives in its own .js file),
// compiled without link-time optimisation: the methods are out of line
// (noinline stands for the file boundary). In one translation unit GCC 12
// inlines them all and elides the heap allocations; it then measures
// 1.3-2.0e8 pairs/s instead.
namespace learner {

constexpr double G = 1.0;

class Vector {
 public:
  double x;
  double y;
  Vector(double x_, double y_) : x(x_), y(y_) {}
  static std::unique_ptr<Vector> sub(const Vector& a, const Vector& b);
  static std::unique_ptr<Vector> div(const Vector& v, double n);
  double mag() const;
  void add(const Vector& v);
  void mult(double n);
  void normalize();
  void setMag(double n);
};

// --- Vector.cpp ---
[[gnu::noinline]] std::unique_ptr<Vector> Vector::sub(const Vector& a, const Vector& b) {
  return std::make_unique<Vector>(a.x - b.x, a.y - b.y);
}
[[gnu::noinline]] std::unique_ptr<Vector> Vector::div(const Vector& v, double n) {
  return std::make_unique<Vector>(v.x / n, v.y / n);
}
[[gnu::noinline]] double Vector::mag() const { return std::sqrt(x * x + y * y); }
[[gnu::noinline]] void Vector::add(const Vector& v) {
  x += v.x;
  y += v.y;
}
[[gnu::noinline]] void Vector::mult(double n) {
  x *= n;
  y *= n;
}
[[gnu::noinline]] void Vector::normalize() {
  const double len = mag();
  if (len != 0) mult(1 / len);
}
[[gnu::noinline]] void Vector::setMag(double n) {
  normalize();
  mult(n);
}

double constrain(double v, double lo, double hi) { return std::max(lo, std::min(v, hi)); }

class Mover {
 public:
  Mover(double x, double y, double m)
      : position(x, y), velocity(0, 0), acceleration(0, 0), mass(m) {}
  std::unique_ptr<Vector> attract(const Mover& mover) const;
  void applyForce(const Vector& force);

  Vector position;
  Vector velocity;
  Vector acceleration;
  double mass;
};

// --- Mover.cpp ---
[[gnu::noinline]] std::unique_ptr<Vector> Mover::attract(const Mover& mover) const {
  std::unique_ptr<Vector> force = Vector::sub(position, mover.position);
  double distance = force->mag();
  distance = constrain(distance, 5, 25);
  const double strength = (G * mass * mover.mass) / (distance * distance);
  force->setMag(strength);
  return force;
}

[[gnu::noinline]] void Mover::applyForce(const Vector& force) {
  std::unique_ptr<Vector> f = Vector::div(force, mass);
  acceleration.add(*f);
}

}  // namespace learner

void Learner(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const System& s = cached_disk(n);
  std::vector<learner::Mover> movers;
  for (std::size_t i = 0; i < n; ++i) movers.emplace_back(s.x[i], s.y[i], s.m[i]);
  for (auto _ : state) {
    for (std::size_t i = 0; i < movers.size(); i++) {
      for (std::size_t j = 0; j < movers.size(); j++) {
        if (i != j) {
          std::unique_ptr<learner::Vector> force = movers[j].attract(movers[i]);
          movers[i].applyForce(*force);
        }
      }
    }
    benchmark::DoNotOptimize(movers.data());
    for (auto& mover : movers) mover.acceleration = learner::Vector(0, 0);
  }
  const double pairs = static_cast<double>(n) * static_cast<double>(n);
  state.counters["pairs/s"] = benchmark::Counter(pairs * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(Learner)->ArgName("N")->Arg(1000)->Arg(4000)->UseRealTime()->Unit(
    benchmark::kMillisecond);
BENCHMARK(Learner)->ArgName("N")->Arg(16000)->Iterations(1)->UseRealTime()->Unit(
    benchmark::kMillisecond);

// -------------------------------------------------------------- FMA floor ---

// Flops of one interaction, counting an FMA as 2 and every other arithmetic
// instruction (add, sub, mul, div, sqrt, rsqrt estimate) as 1, as the
// kernels compile (objdump of kernels.cpp.o), Plummer law, eps > 0:
//   float32, rsqrt estimate + 1 Newton step:   2 sub, 4 FMA, 1 rsqrt, 5 mul  = 18
//   float64, avx512: rsqrt14 + 2 Newton steps: 2 sub, 6 FMA, 1 rsqrt, 8 mul  = 23
//   float64, avx2 / sse2: sqrt + div:          2 sub, 4 FMA, 1 sqrt, 1 mul, 1 div = 13
constexpr double kFlops32 = 18.0;
constexpr double kFlops64Rsqrt = 23.0;
constexpr double kFlops64Sqrt = 13.0;

using Float128 = float __attribute__((vector_size(16)));
using Float256 = float __attribute__((vector_size(32)));
using Float512 = float __attribute__((vector_size(64)));

// 12 independent chains of FMAs on vectors V; returns the flops done. (This
// file is compiled with -ffp-contract=fast: acc * a + b is one vfmadd.)
template <typename V>
double fma_chains(std::int64_t rounds) {
  constexpr std::size_t kLanes = sizeof(V) / sizeof(float);
  V acc[12];
  V a;
  V b;
  for (std::size_t k = 0; k < kLanes; ++k) {
    a[k] = 0.999999f;
    b[k] = 1e-7f;
    for (std::size_t c = 0; c < 12; ++c) acc[c][k] = static_cast<float>(c) * 0.1f;
  }
  for (std::int64_t r = 0; r < rounds; ++r) {
    for (std::size_t c = 0; c < 12; ++c) acc[c] = acc[c] * a + b;  // one vfmadd each
    asm volatile("" : "+v"(a));  // keep the loop from being folded
  }
  V sum = acc[0];
  for (std::size_t c = 1; c < 12; ++c) sum += acc[c];
  benchmark::DoNotOptimize(sum);
  return 2.0 * 12.0 * static_cast<double>(kLanes) * static_cast<double>(rounds);
}

template <typename V>
void FmaPeak(benchmark::State& state) {
  const auto threads = static_cast<std::size_t>(state.range(1));
  constexpr std::int64_t kRounds = 20'000'000;
  double flops = 0.0;
  for (auto _ : state) {
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back([] { fma_chains<V>(kRounds); });
    flops += fma_chains<V>(kRounds);
    for (auto& t : pool) t.join();
  }
  flops *= static_cast<double>(threads);
  state.counters["flops/s"] = benchmark::Counter(flops, benchmark::Counter::kIsRate);
  // Per-precision floors: float32 uses V-wide vectors of floats; float64
  // the same width of doubles (half the lanes, so half the flops/s).
  state.counters["floor32_pairs/s"] =
      benchmark::Counter(flops / kFlops32, benchmark::Counter::kIsRate);
  state.counters["floor64_rsqrt_pairs/s"] =
      benchmark::Counter(flops / 2.0 / kFlops64Rsqrt, benchmark::Counter::kIsRate);
  state.counters["floor64_sqrt_pairs/s"] =
      benchmark::Counter(flops / 2.0 / kFlops64Sqrt, benchmark::Counter::kIsRate);
}
#if defined(__AVX512F__)
BENCHMARK(FmaPeak<Float512>)
    ->ArgNames({"bits", "threads"})
    ->Args({512, 1})
    ->Args({512, 2})
    ->UseRealTime();
#endif
#if defined(__AVX__)
BENCHMARK(FmaPeak<Float256>)
    ->ArgNames({"bits", "threads"})
    ->Args({256, 1})
    ->Args({256, 2})
    ->UseRealTime();
#endif
BENCHMARK(FmaPeak<Float128>)
    ->ArgNames({"bits", "threads"})
    ->Args({128, 1})
    ->Args({128, 2})
    ->UseRealTime();

// -------------------------------------------------------------- Barnes-Hut ---

struct Sampled {
  std::vector<std::size_t> bodies;  // where the error is measured
  std::vector<double> ax;           // their direct-sum accelerations
  std::vector<double> ay;
};

// The exact accelerations of all bodies (N <= 10^4: direct, float64) or of
// 256 random ones (reference_acceleration).
const Sampled& exact(const System& s, const nb::Options& o, const std::string& key) {
  static std::map<std::string, Sampled> cache;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  Sampled e;
  const std::size_t n = s.x.size();
  if (n <= 10000) {
    e.ax.assign(n, 0.0);
    e.ay.assign(n, 0.0);
    nb::Options d = o;
    d.precision = nb::Precision::float64;
    d.threads = 0;
    nb::direct_accelerations(s.x, s.y, s.m, e.ax, e.ay, d);
    for (std::size_t i = 0; i < n; ++i) e.bodies.push_back(i);
  } else {
    std::mt19937_64 g(7);
    for (int k = 0; k < 256; ++k) {
      const std::size_t i = static_cast<std::size_t>(g() % n);
      const calder::Vec2 a = nb::reference_acceleration(s.x, s.y, s.m, i, o);
      e.bodies.push_back(i);
      e.ax.push_back(a.x);
      e.ay.push_back(a.y);
    }
  }
  return cache.emplace(key, std::move(e)).first->second;
}

void report_error(benchmark::State& state, const Sampled& e, const std::vector<double>& ax,
                  const std::vector<double>& ay) {
  double sum = 0.0;
  double max = 0.0;
  for (std::size_t k = 0; k < e.bodies.size(); ++k) {
    const std::size_t i = e.bodies[k];
    const double rel = std::hypot(ax[i] - e.ax[k], ay[i] - e.ay[k]) / std::hypot(e.ax[k], e.ay[k]);
    sum += rel * rel;
    max = std::max(max, rel);
  }
  state.counters["rms_err"] = std::sqrt(sum / static_cast<double>(e.bodies.size()));
  state.counters["max_err"] = max;
}

void BarnesHut(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const System& s = cached_disk(n);
  nb::BarnesHutOptions o;
  static_cast<nb::Options&>(o) = options_for(state.range(1), state.range(2), 0);
  o.theta = static_cast<double>(state.range(3)) / 100.0;
  const Sampled& e = exact(s, o, "disk" + std::to_string(n));
  nb::BarnesHut solver;
  std::vector<double> ax(n);
  std::vector<double> ay(n);
  double build = 0.0;
  for (auto _ : state) {
    std::fill(ax.begin(), ax.end(), 0.0);
    std::fill(ay.begin(), ay.end(), 0.0);
    solver.accelerations(s.x, s.y, s.m, ax, ay, o);
    build += solver.stats().build_seconds;
    benchmark::DoNotOptimize(ax.data());
  }
  state.counters["steps/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["build_ms"] = 1e3 * build / static_cast<double>(state.iterations());
  state.counters["pairs/body"] =
      static_cast<double>(solver.stats().interactions) / static_cast<double>(n);
  report_error(state, e, ax, ay);
}
BENCHMARK(BarnesHut)
    ->ArgNames({"N", "precision", "threads", "theta100"})
    ->ArgsProduct({{10000, 100000, 1000000}, {64, 32}, {1, 2}, {50}})
    ->ArgsProduct({{1000000}, {64, 32}, {1, 2}, {45}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BarnesHutError(benchmark::State& state) {
  constexpr std::size_t n = 10000;
  const bool clustered = state.range(1) != 0;
  static const System uniform_disk = disk(n, 43);
  static const System clumps = clusters(n, 44);
  const System& s = clustered ? clumps : uniform_disk;
  nb::BarnesHutOptions o;
  o.softening = clustered ? 0.05 : kSoftening;
  o.theta = static_cast<double>(state.range(0)) / 100.0;
  o.threads = 2;
  const Sampled& e = exact(s, o, clustered ? "clusters" : "disk");
  std::vector<double> ax(n);
  std::vector<double> ay(n);
  nb::BarnesHut solver;
  for (auto _ : state) {
    std::fill(ax.begin(), ax.end(), 0.0);
    std::fill(ay.begin(), ay.end(), 0.0);
    solver.accelerations(s.x, s.y, s.m, ax, ay, o);
  }
  state.counters["pairs/body"] =
      static_cast<double>(solver.stats().interactions) / static_cast<double>(n);
  report_error(state, e, ax, ay);
}
BENCHMARK(BarnesHutError)
    ->ArgNames({"theta100", "clusters"})
    ->ArgsProduct({{20, 30, 40, 50, 60, 70, 80, 100}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::AddCustomContext("calder_nbody_kernels", nb::kernel_name());
  benchmark::AddCustomContext("calder_nbody_max_threads", std::to_string(nb::max_threads()));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
