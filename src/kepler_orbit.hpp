// SPDX-License-Identifier: MIT
// A body started at the pericentre of a Kepler orbit: the built-in `kepler`
// scene and a scene file's `kepler = { ... }` key make it the same way, so
// that the two give the same bits.
#pragma once

#include <cmath>

namespace calder::detail {

struct Pericentre {
  double distance = 0.0;  // q = a (1 - e), from the focus
  double speed = 0.0;     // perpendicular to the focus-body line
};

// The orbit of semi-major axis a and eccentricity e (0 <= e < 1) about a
// mass whose G M is gm. q is a - a e, within a rounding of a (1 - e): the
// decimal e's own pericentre (10 for a = 100, e = 0.9). The speed is
// vis-viva's at r = q: v^2 = gm (2 / q - 1 / a) = gm (1 + e) / q.
inline Pericentre pericentre(double gm, double semi_major_axis, double eccentricity) {
  const double q = semi_major_axis - semi_major_axis * eccentricity;
  return {q, std::sqrt(gm * (1.0 + eccentricity) / q)};
}

}  // namespace calder::detail
