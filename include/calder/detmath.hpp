// SPDX-License-Identifier: MIT
// calder: the elementary functions that scenes compute with, calder's own, so
// that a run gives the same bits on every platform and in p5.js.
//
// The C library's sin, cos, pow, ... differ in the last bit between glibc,
// musl (Emscripten), Apple's libm and MSVC's, and p5.js computes with V8's
// Math, a third implementation. One bit in a chaotic scene becomes a different
// state, so calder does not call the C library for them: these functions are
// written in plain IEEE double arithmetic (compiled with -ffp-contract=off,
// integer bit manipulation, no long double, no fused multiply-add) and follow
// the algorithms and coefficients of fdlibm 5.3 (Sun Microsystems, 1993,
// netlib.org/fdlibm), which is what V8's Math.sin, cos, atan2, log and pow run
// (V8's src/base/ieee754.cc; Math.pow is its "legacy" fdlibm pow). They give
// V8's results bit for bit; tests/test_detmath.cpp holds them to Node's Math
// on hundreds of thousands of arguments (tests/data/detmath_v8.txt).
//
// The special values are JavaScript's: pow(+-1, +-inf) and pow(1, NaN) are
// NaN, unlike C's pow. Accuracy: within 1 ulp (fdlibm's bound), usually the
// correctly rounded result.
#pragma once

namespace calder::math {

// sin x and cos x (x in radians), with fdlibm's exact argument reduction for
// huge |x| (Payne-Hanek with 2/pi to 1584 bits).
[[nodiscard]] double sin(double x);
[[nodiscard]] double cos(double x);

// The principal arc tangent of x, in [-pi/2, pi/2].
[[nodiscard]] double atan(double x);

// The angle of the point (x, y), in [-pi, pi], with C's and JavaScript's
// special cases (atan2(+-0, -0) = +-pi, ...).
[[nodiscard]] double atan2(double y, double x);

// The natural logarithm; log(0) = -inf, log(x < 0) = NaN.
[[nodiscard]] double log(double x);

// x to the power y, with JavaScript's special cases (Math.pow, `**`).
[[nodiscard]] double pow(double x, double y);

}  // namespace calder::math
