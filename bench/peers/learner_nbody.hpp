// SPDX-License-Identifier: MIT
// The book's example 2.9 (mutual attraction) as a learner ports it from p5.js
// to C++: a Vector class with p5.Vector's methods, the static ones
// (p5.Vector.sub, p5.Vector.div) returning a new vector on the heap, and Mover
// objects holding vectors; attract() and applyForce() are the book's, line for
// line, with its clamp of the distance to [5, 25]. The peer that calder's
// direct n-body kernels are measured against, on one thread.
// One definition for bench_nbody, `calder bench` and their tests.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace calder::peers {

namespace learner {

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

}  // namespace learner

// N movers and the book's double loop over them.
class LearnerNBody {
 public:
  // One mover per body (equal-size spans).
  LearnerNBody(std::span<const double> x, std::span<const double> y, std::span<const double> mass);

  // The book's draw() loop for the targets i in [first, last): for every
  // j != i, movers[j].attract(movers[i]) and movers[i].applyForce(force).
  // attract(0, size()) is one whole evaluation (size()^2 pairs, counting the
  // skipped self pairs as calder's kernels do); a slice of it runs the same
  // inner loop, for timing large N without a whole evaluation.
  void attract(std::size_t first, std::size_t last);
  // Zeroes the accelerations (what update() would do after moving).
  void clear();

  std::size_t size() const { return movers_.size(); }
  const learner::Mover& mover(std::size_t i) const { return movers_[i]; }

 private:
  std::vector<learner::Mover> movers_;
};

}  // namespace calder::peers
