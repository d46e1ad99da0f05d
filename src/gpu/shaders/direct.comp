// SPDX-License-Identifier: MIT
// calder::gpu: direct n-body sums (src/gpu/direct.cpp). One target per
// invocation; the workgroup reads the sources a tile at a time into shared
// memory, each invocation summing the tile's pulls on its target in source
// order. No atomics: a target's sum is one invocation's, in a fixed order,
// so the same device gives the same bits every run.
//
//   w = 1 / (r^2 + eps^2)^(3/2)        kLaw kLawPlummer
//   w = 1 / (r d^2), d = clamp(r)      kLaw kLawClampDistance, the book's clamp
//   w = 1 / (r q),   q = clamp(r^2)    kLaw kLawClampSquaredDistance
//   sum += m_s w (p_s - p_t), w = 0 where p_s == p_t (kMask)
//
// FLOAT64 defined: doubles throughout. The square root's reciprocal and the
// clamps' reciprocals start from float estimates refined by Newton steps in
// double, which need only multiplications and additions (correctly rounded
// in Vulkan; its double sqrt and divide need only float's precision).
// Otherwise float32: positions relative to the bodies' centre as two floats
// (hi, lo), so that each difference keeps float's precision however close
// the pair; a tile's sum in float, the tiles' sums added with the rounding
// error kept (TwoSum), the pair (sum, error) written out.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "interface.h"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const int kLaw = kLawPlummer;
layout(constant_id = 2) const int kMask = 1;

#ifdef FLOAT64
#define REAL double
#define REAL2 dvec2
#else
#define REAL float
#define REAL2 vec2
#endif

layout(push_constant) uniform Push {
  uint n_pad;   // sources and targets, a whole number of workgroups
  uint groups;  // n_pad / the workgroup size
  REAL eps2;    // Plummer: softening^2
  REAL lo;      // clamp bounds (distance, or squared distance)
  REAL hi;
} p;

#ifdef FLOAT64
layout(std430, binding = 0) readonly buffer Positions { dvec2 pos[]; };
layout(std430, binding = 1) readonly buffer Masses { double mass[]; };
layout(std430, binding = 2) writeonly buffer Sums { dvec2 sums[]; };
shared dvec2 tile_pos[gl_WorkGroupSize.x];
#else
layout(std430, binding = 0) readonly buffer Positions { vec4 pos[]; };  // x, y, x_lo, y_lo
layout(std430, binding = 1) readonly buffer Masses { float mass[]; };
layout(std430, binding = 2) writeonly buffer Sums { vec4 sums[]; };  // sum x, y, error x, y
shared vec4 tile_pos[gl_WorkGroupSize.x];
#endif
shared REAL tile_m[gl_WorkGroupSize.x];

#ifdef FLOAT64
// 1 / sqrt(v), v > 0: v = f 2^(2k), f in [0.5, 2); float's estimate of
// 1 / sqrt(f), two Newton steps (relative error 2^-22 -> 2^-43 -> below
// double's rounding).
double rsqrt64(double v) {
  int e;
  double f = frexp(v, e);
  if ((e & 1) != 0) {
    f *= 2.0;
    e -= 1;
  }
  double y = double(inversesqrt(float(f)));
  const double h = 0.5 * f;
  y = y * (1.5 - h * y * y);
  y = y * (1.5 - h * y * y);
  return ldexp(y, -(e / 2));
}

// 1 / v, v > 0: v = f 2^k, f in [0.5, 1); float's estimate, two Newton steps.
double recip64(double v) {
  int e;
  const double f = frexp(v, e);
  double y = double(1.0 / float(f));
  y = y * (2.0 - f * y);
  y = y * (2.0 - f * y);
  return ldexp(y, -e);
}
#endif

void main() {
  const uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  if (group >= p.groups) return;  // the fold's spare groups (the whole workgroup)
  const uint local = gl_LocalInvocationID.x;
  const uint i = group * gl_WorkGroupSize.x + local;
#ifdef FLOAT64
  const dvec2 me = pos[i];
  dvec2 total = dvec2(0.0);
#else
  const vec4 me = pos[i];
  precise vec2 total = vec2(0.0);
  precise vec2 error = vec2(0.0);
#endif
  for (uint base = 0; base < p.n_pad; base += gl_WorkGroupSize.x) {
    barrier();
    tile_pos[local] = pos[base + local];
    tile_m[local] = mass[base + local];
    barrier();
    REAL2 part = REAL2(0.0);
    for (uint k = 0; k < gl_WorkGroupSize.x; ++k) {
#ifdef FLOAT64
      const dvec2 s = tile_pos[k];
      const double dx = s.x - me.x;
      const double dy = s.y - me.y;
      const double r2 = dx * dx + dy * dy;
      double w;
      if (kLaw == kLawPlummer) {
        const double inv = rsqrt64(r2 + p.eps2);
        w = inv * inv * inv;
      } else if (kLaw == kLawClampDistance) {
        const double inv = rsqrt64(r2);
        const double d = clamp(r2 * inv, p.lo, p.hi);
        w = inv * recip64(d * d);
      } else {
        const double inv = rsqrt64(r2);
        w = inv * recip64(clamp(r2, p.lo, p.hi));
      }
      w *= tile_m[k];
      if (kMask != 0) w = r2 > 0.0 ? w : 0.0;
#else
      const vec4 s = tile_pos[k];
      const float dx = (s.x - me.x) + (s.z - me.z);
      const float dy = (s.y - me.y) + (s.w - me.w);
      const float r2 = dx * dx + dy * dy;
      float w;
      if (kLaw == kLawPlummer) {
        const float inv = inversesqrt(r2 + p.eps2);
        w = inv * inv * inv;
      } else if (kLaw == kLawClampDistance) {
        const float inv = inversesqrt(r2);
        const float d = clamp(r2 * inv, p.lo, p.hi);
        w = inv / (d * d);
      } else {
        w = inversesqrt(r2) / clamp(r2, p.lo, p.hi);
      }
      w *= tile_m[k];
      if (kMask != 0) w = r2 > 0.0 ? w : 0.0;
#endif
      part += w * REAL2(dx, dy);
    }
#ifdef FLOAT64
    total += part;
#else
    // TwoSum: t = total + part exactly as t + its rounding error.
    precise vec2 t = total + part;
    precise vec2 back = t - total;
    error += (total - (t - back)) + (part - back);
    total = t;
#endif
  }
#ifdef FLOAT64
  sums[i] = total;
#else
  sums[i] = vec4(total, error);
#endif
}
