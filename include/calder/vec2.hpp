// SPDX-License-Identifier: MIT
// calder: Vec2, a 2D vector with the p5.Vector vocabulary of the book.
//
// Vec2 is a value type: copying it copies the numbers. A function that takes a
// Vec2 (apply_force among them) works on its own copy, so the aliasing bug of
// the book's first applyForce (dividing the caller's force by the mass) cannot
// happen. The member functions that p5 uses to change a vector in place (add,
// sub, mult, div, normalize, set_mag, limit, rotate, lerp) change *this and
// return it, so p5 chains read the same; the operators return new vectors.
//
// The arithmetic follows p5.js exactly (see shared/spec/chapter2.md), because
// the last bits decide whether a ported sketch reproduces its original:
// mag() is sqrt(x*x + y*y) (not hypot), normalize() multiplies by 1/mag, and a
// zero vector stays zero under normalize() and set_mag().
#pragma once

#include <cmath>

#include "calder/detmath.hpp"
#include "calder/error.hpp"

namespace calder {

class Random;

struct Vec2 {
  double x = 0.0;
  double y = 0.0;

  // --- in-place operations (p5: v.add(w), v.mult(2), ...) ---
  constexpr Vec2& add(Vec2 v) {
    x += v.x;
    y += v.y;
    return *this;
  }
  constexpr Vec2& sub(Vec2 v) {
    x -= v.x;
    y -= v.y;
    return *this;
  }
  constexpr Vec2& mult(double n) {
    x *= n;
    y *= n;
    return *this;
  }
  // Divides both components by n. Throws calder::Error for n == 0 (p5 warns
  // and leaves the vector unchanged; a library should not hide it).
  Vec2& div(double n) {
    if (n == 0.0) throw Error("Vec2::div: division by zero");
    x /= n;
    y /= n;
    return *this;
  }
  // If the length is not zero, multiplies by 1 / length; a zero vector stays zero.
  Vec2& normalize() {
    const double len = mag();
    if (len != 0.0) mult(1.0 / len);
    return *this;
  }
  // normalize() then mult(len): a zero vector stays zero.
  Vec2& set_mag(double len) { return normalize().mult(len); }
  // If |v| > max: divide by |v| then multiply by max (p5's order of operations).
  Vec2& limit(double max) {
    const double m_sq = mag_sq();
    if (m_sq > max * max) {
      div(std::sqrt(m_sq));
      mult(max);
    }
    return *this;
  }
  // Rotates by angle radians the way p5 does: heading() + angle, same length.
  Vec2& rotate(double angle) {
    const double new_heading = heading() + angle;
    const double len = mag();
    x = math::cos(new_heading) * len;
    y = math::sin(new_heading) * len;
    return *this;
  }
  // Moves toward v by the fraction amount (p5: x += (v.x - x) * amount).
  constexpr Vec2& lerp(Vec2 v, double amount) {
    x += (v.x - x) * amount;
    y += (v.y - y) * amount;
    return *this;
  }
  constexpr Vec2& set(double new_x, double new_y) {
    x = new_x;
    y = new_y;
    return *this;
  }

  // --- queries ---
  [[nodiscard]] double mag() const { return std::sqrt(x * x + y * y); }
  [[nodiscard]] constexpr double mag_sq() const { return x * x + y * y; }
  // Angle of the vector in radians, atan2(y, x).
  [[nodiscard]] double heading() const { return math::atan2(y, x); }
  [[nodiscard]] double dist(Vec2 v) const { return Vec2{v.x - x, v.y - y}.mag(); }
  [[nodiscard]] constexpr double dot(Vec2 v) const { return x * v.x + y * v.y; }
  // z component of the 3D cross product (x1*y2 - y1*x2).
  [[nodiscard]] constexpr double cross(Vec2 v) const { return x * v.y - y * v.x; }
  [[nodiscard]] constexpr Vec2 copy() const { return *this; }
  [[nodiscard]] bool is_finite() const { return std::isfinite(x) && std::isfinite(y); }

  // --- p5's static constructors ---
  // (length * cos(angle), length * sin(angle)).
  [[nodiscard]] static Vec2 from_angle(double angle, double length = 1.0) {
    return {length * math::cos(angle), length * math::sin(angle)};
  }
  // A unit vector at a uniform random angle drawn from rng (defined in random.hpp).
  [[nodiscard]] static Vec2 random2d(Random& rng);
  // Same, drawn from the default generator of calder/random.hpp.
  [[nodiscard]] static Vec2 random2d();

  friend constexpr bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
  friend constexpr bool operator!=(Vec2 a, Vec2 b) { return !(a == b); }
};

// --- operators: new vectors, never aliases ---
constexpr Vec2 operator+(Vec2 a, Vec2 b) { return a.add(b); }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return a.sub(b); }
constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
constexpr Vec2 operator*(Vec2 a, double n) { return a.mult(n); }
constexpr Vec2 operator*(double n, Vec2 a) { return a.mult(n); }
inline Vec2 operator/(Vec2 a, double n) { return a.div(n); }
constexpr Vec2& operator+=(Vec2& a, Vec2 b) { return a.add(b); }
constexpr Vec2& operator-=(Vec2& a, Vec2 b) { return a.sub(b); }
constexpr Vec2& operator*=(Vec2& a, double n) { return a.mult(n); }
inline Vec2& operator/=(Vec2& a, double n) { return a.div(n); }

// --- p5's static forms: p5.Vector.add(a, b) and friends return new vectors ---
constexpr Vec2 add(Vec2 a, Vec2 b) { return a + b; }
constexpr Vec2 sub(Vec2 a, Vec2 b) { return a - b; }
constexpr Vec2 mult(Vec2 a, double n) { return a * n; }
inline Vec2 div(Vec2 a, double n) { return a / n; }
inline double dist(Vec2 a, Vec2 b) { return a.dist(b); }
constexpr double dot(Vec2 a, Vec2 b) { return a.dot(b); }
constexpr double cross(Vec2 a, Vec2 b) { return a.cross(b); }
constexpr Vec2 lerp(Vec2 a, Vec2 b, double amount) { return a.lerp(b, amount); }

}  // namespace calder
