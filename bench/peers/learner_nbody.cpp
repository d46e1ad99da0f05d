// SPDX-License-Identifier: MIT
// Each class would live in its own .cpp (as each lives in its own .js file),
// compiled without link-time optimisation: the methods are out of line
// (noinline stands for the file boundary). In one translation unit GCC 12
// inlines them all and elides the heap allocations; it then measures
// 1.3-2.0e8 pairs/s instead.
#include "peers/learner_nbody.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace calder::peers {

namespace learner {

namespace {

constexpr double G = 1.0;

double constrain(double v, double lo, double hi) { return std::max(lo, std::min(v, hi)); }

}  // namespace

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

LearnerNBody::LearnerNBody(std::span<const double> x, std::span<const double> y,
                           std::span<const double> mass) {
  if (y.size() != x.size() || mass.size() != x.size()) {
    throw std::invalid_argument("LearnerNBody: x, y and mass differ in size");
  }
  movers_.reserve(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) movers_.emplace_back(x[i], y[i], mass[i]);
}

// --- sketch.js, draw() ---
void LearnerNBody::attract(std::size_t first, std::size_t last) {
  last = std::min(last, movers_.size());
  for (std::size_t i = first; i < last; i++) {
    for (std::size_t j = 0; j < movers_.size(); j++) {
      if (i != j) {
        std::unique_ptr<learner::Vector> force = movers_[j].attract(movers_[i]);
        movers_[i].applyForce(*force);
      }
    }
  }
}

void LearnerNBody::clear() {
  for (auto& mover : movers_) mover.acceleration = learner::Vector(0, 0);
}

}  // namespace calder::peers
