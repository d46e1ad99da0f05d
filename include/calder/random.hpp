// SPDX-License-Identifier: MIT
// calder: random numbers and Perlin noise that match p5.js 2.x bit for bit.
//
// A sketch ported from p5.js starts from the same world as the original when
// it draws the same values in the same order after the same seeds. The
// algorithms are p5's (shared/spec/chapter2.md, "Random numbers and noise"):
//   random:  a linear congruential generator, state = 1664525 * state +
//            1013904223 (mod 2^32), each draw = state / 2^32 in [0, 1);
//   gaussian: polar Box-Muller on random(2) - 1 pairs, the second value kept;
//   noise:   p5's value noise over a 4096-entry table filled by its own LCG,
//            4 octaves, amplitude 0.5 halving each octave, cosine blending.
//
// Random and Noise are plain objects: a World owns one of each, tests and
// threads make their own. The free functions below (random(), noise(), ...)
// use one process-wide pair, like the globals of a p5 sketch; they are for
// book-style single-threaded programs.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "calder/vec2.hpp"

namespace calder {

class Random {
 public:
  // Seeded like randomSeed(seed).
  explicit Random(std::uint32_t seed = 0) { random_seed(seed); }

  // p5 randomSeed(s): state = s as an unsigned 32-bit integer; also forgets a
  // kept Gaussian value.
  void random_seed(std::uint32_t seed);
  // randomSeed with a JavaScript number: converted like `s >>> 0` (truncated
  // toward zero, modulo 2^32). Throws calder::Error for NaN or infinity.
  void random_seed(double seed);
  // randomSeed(1) with a plain int literal: as the JavaScript number.
  void random_seed(int seed) { random_seed(static_cast<double>(seed)); }

  // p5 random(): uniform in [0, 1). The forms with arguments throw
  // calder::Error for NaN or infinite bounds (p5 would return NaN).
  double random();
  // p5 random(max): random() * max.
  double random(double max);
  // p5 random(min, max): uniform in [min, max) (the bounds are swapped first
  // when min > max).
  double random(double min, double max);
  // p5 randomGaussian(mean, sd).
  double random_gaussian(double mean = 0.0, double sd = 1.0);
  // A unit vector at angle random() * 2 pi. (p5's p5.Vector.random2D draws
  // from Math.random, which randomSeed does not seed; calder draws from this
  // generator so that a seed fixes the whole world.)
  Vec2 random2d();

  // The raw 32-bit state, e.g. to save and restore a generator.
  [[nodiscard]] std::uint32_t state() const { return state_; }
  // The second value of the last Box-Muller pair, kept for the next
  // random_gaussian(); none when the next call draws a new pair.
  [[nodiscard]] std::optional<double> spare_gaussian() const;
  // Puts back a saved generator: its state and kept Gaussian value (a
  // snapshot, calder/snapshot.hpp). Throws calder::Error for a kept value
  // that is not finite.
  void restore(std::uint32_t state, std::optional<double> spare_gaussian);

 private:
  std::uint32_t state_ = 0;
  bool has_spare_gaussian_ = false;
  double spare_gaussian_ = 0.0;
};

class Noise {
 public:
  static constexpr int table_size = 4096;

  // Seeded like noiseSeed(seed).
  explicit Noise(std::uint32_t seed = 0) { noise_seed(seed); }

  // p5 noiseSeed(s): refills the table with 4096 draws of an LCG seeded with s.
  void noise_seed(std::uint32_t seed);
  // p5 noiseSeed with a JavaScript number (`s >>> 0`, as random_seed).
  void noise_seed(double seed);
  void noise_seed(int seed) { noise_seed(static_cast<double>(seed)); }
  // p5 noiseDetail(octaves, falloff). Defaults: 4 octaves, falloff 0.5.
  // Throws calder::Error for octaves outside [1, kMaxOctaves] or a falloff
  // that is not finite.
  void noise_detail(int octaves, double falloff = 0.5);
  // Each sample costs one pass a octave; past 64, an octave at a falloff
  // below 1 adds less than 2^-64 of the first one's amplitude.
  static constexpr int kMaxOctaves = 64;

  // p5 noise(x, y, z) in [0, 1). Throws calder::Error for NaN or infinite input.
  [[nodiscard]] double noise(double x, double y = 0.0, double z = 0.0) const;

  // What the generator is made of (its table follows from the seed): a
  // snapshot saves these and puts them back with noise_seed and noise_detail.
  [[nodiscard]] std::uint32_t seed() const { return seed_; }
  [[nodiscard]] int octaves() const { return octaves_; }
  [[nodiscard]] double falloff() const { return falloff_; }

 private:
  std::array<double, table_size> table_{};
  std::uint32_t seed_ = 0;
  int octaves_ = 4;
  double falloff_ = 0.5;
};

// --- book-style globals (one process-wide generator pair, not thread-safe) ---
Random& default_random();
Noise& default_noise();

void random_seed(std::uint32_t seed);
void random_seed(double seed);
void random_seed(int seed);
double random();
double random(double max);
double random(double min, double max);
double random_gaussian(double mean = 0.0, double sd = 1.0);
void noise_seed(std::uint32_t seed);
void noise_seed(double seed);
void noise_seed(int seed);
void noise_detail(int octaves, double falloff = 0.5);
double noise(double x, double y = 0.0, double z = 0.0);

// p5 map(value, start1, stop1, start2, stop2), with p5's grouping:
// (value - start1) / (stop1 - start1) * (stop2 - start2) + start2.
// Throws calder::Error for non-finite input or start1 == stop1.
double map_range(double value, double start1, double stop1, double start2, double stop2);
// p5 constrain(n, low, high) = max(min(n, high), low). Throws for NaN.
double constrain(double n, double low, double high);

}  // namespace calder
