// SPDX-License-Identifier: MIT
// calder::gpu: a batch of whole-world steps (src/gpu/steps.cpp), the fast
// arithmetic of calder::bulk (src/bulk/kernels_impl.hpp, kBook = false): one
// body per invocation, its position and velocity in registers through every
// step of the batch, the ops of the fields in order each step, then
// semi-implicit Euler and the boundary. Bodies don't interact: no shared
// memory, no order between invocations, the same bits every run.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "interface.h"

layout(local_size_x_id = 0) in;
// kFixedOps >= 0: the plan has that many ops (at most 4), of the kinds,
// flags and laws or edges below, fixed when the pipeline is made: the
// compiler then drops the dispatch on kinds and keeps the ops' parameters in
// registers through the batch. -1: any number, read from op_ints.
layout(constant_id = 1) const int kFixedOps = -1;
layout(constant_id = 2) const int kKind0 = 0;
layout(constant_id = 3) const int kKind1 = 0;
layout(constant_id = 4) const int kKind2 = 0;
layout(constant_id = 5) const int kKind3 = 0;
layout(constant_id = 6) const int kFlags0 = 0;
layout(constant_id = 7) const int kFlags1 = 0;
layout(constant_id = 8) const int kFlags2 = 0;
layout(constant_id = 9) const int kFlags3 = 0;
layout(constant_id = 10) const int kWhich0 = 0;
layout(constant_id = 11) const int kWhich1 = 0;
layout(constant_id = 12) const int kWhich2 = 0;
layout(constant_id = 13) const int kWhich3 = 0;

#ifdef FLOAT64
#define REAL double
#define REAL2 dvec2
#define REAL4 dvec4
#else
#define REAL float
#define REAL2 vec2
#define REAL4 vec4
#endif

layout(push_constant) uniform Push {
  uint n;
  uint groups;
  uint steps;      // in this batch
  uint ops;
  uint boundary;   // the flags above
  uint first;      // this batch's first step, for per-step forces
  uint total;      // steps of the whole call (per-step forces' stride)
  uint pad;
  REAL dt, width, height, reverse;  // reverse: -restitution
  REAL cx, cy;                      // constant accelerations (gravity scaled by mass)
} p;

layout(std430, binding = 0) buffer State { REAL4 state[]; };          // x, y, vx, vy
layout(std430, binding = 1) buffer Accel { REAL2 accel[]; };          // applied by hand
layout(std430, binding = 2) readonly buffer Props { REAL4 props[]; }; // 1/m, radius, mu, area
layout(std430, binding = 3) readonly buffer OpInts { ivec4 op_ints[]; };  // kind, flags, law/edge, per-step
layout(std430, binding = 4) readonly buffer OpReals { REAL op_reals[]; }; // kSlots per op
layout(std430, binding = 5) readonly buffer PerStep { REAL per_step[]; };
layout(std430, binding = 6) buffer Bad { uint first_bad; };

// An op's reals by their slot (interface.h; steps.cpp's encode functions
// write them).
REAL prm(int op, int k) { return op_reals[kSlots * op + k]; }

// The acceleration of op `op` on a body (x, y, vx, vy), its properties q;
// k: its kind, flags, law or edge, and per-step forces' offset.
REAL2 op_accel(int op, ivec4 k, uint step, REAL4 b, REAL4 q) {
  const REAL inv_m = q.x;
  if (k.x == kOpUniform) {
    if ((k.y & kOpPerStep) != 0) {
      const uint at = uint(k.w) + 2u * step;
      return REAL2(per_step[at], per_step[at + 1u]) * inv_m;
    }
    return REAL2(prm(op, kSlotFx), prm(op, kSlotFy)) * inv_m;
  }
  if (k.x == kOpDrag || k.x == kOpFriction) {
    const REAL speed = sqrt(b.z * b.z + b.w * b.w);
    bool apply;
    REAL c;
    if (k.x == kOpDrag) {
      apply = (k.y & kOpEverywhere) != 0 ||
              (b.x > prm(op, kSlotXMin) && b.x < prm(op, kSlotXMax) && b.y > prm(op, kSlotYMin) &&
               b.y < prm(op, kSlotYMax));
      c = prm(op, kSlotC) * q.w * speed * inv_m;
    } else {
      const REAL r = q.y;
      const REAL tol = prm(op, kSlotTolerance);
      apply = k.z == kEdgeLeft    ? b.x < r + tol
              : k.z == kEdgeRight ? b.x > p.width - r - tol
              : k.z == kEdgeTop   ? b.y < r + tol
                                  : b.y > p.height - r - tol;
      const REAL mu = q.z < REAL(0) ? prm(op, kSlotC) : q.z;  // -1: none of its own
      c = speed != REAL(0) ? mu * prm(op, kSlotNormal) * inv_m / speed : REAL(0);
    }
    if ((k.y & kOpNeverReverse) != 0) c = min(c, REAL(1) / p.dt);
    return apply ? -c * b.zw : REAL2(0);
  }
  if (k.x == kOpAttractor) {
    const REAL2 r = REAL2(prm(op, kSlotPx), prm(op, kSlotPy)) - b.xy;
    const REAL d_sq = dot(r, r);
    const REAL d = sqrt(d_sq);
    REAL den;
    if (k.z == kLawClampDistance) {
      const REAL dc = clamp(d, prm(op, kSlotLo), prm(op, kSlotHi));
      den = dc * dc * d;
    } else if (k.z == kLawClampSquaredDistance) {
      den = clamp(d_sq, prm(op, kSlotLo), prm(op, kSlotHi)) * d;
    } else {
      const REAL eps = prm(op, kSlotEps);
      const REAL s_sq = d_sq + eps * eps;
      den = s_sq * sqrt(s_sq);
    }
    return d_sq == REAL(0) ? REAL2(0) : prm(op, kSlotGm) / den * r;
  }
  if (k.x == kOpEdgeForce) {
    const REAL margin = prm(op, kSlotReach);
    const REAL c = prm(op, kSlotC);
    const REAL4 d = REAL4(b.x, p.width - b.x, b.y, p.height - b.y);
    REAL4 push = c * (margin - d) / margin;
    push = mix(REAL4(0), push, lessThan(d, REAL4(margin)));
    return REAL2(push.x - push.y, push.z - push.w) * inv_m;
  }
  if (k.x == kOpFan) {
    const REAL2 away = b.xy - REAL2(prm(op, kSlotPx), prm(op, kSlotPy));
    const REAL d = length(away);
    const REAL reach = prm(op, kSlotReach);
    if (!(d != REAL(0) && d < reach)) return REAL2(0);
    return away * (REAL(1) / d) * (prm(op, kSlotC) * (REAL(1) - d / reach)) * inv_m;
  }
  if (k.x == kOpLift) {
    const REAL magnitude = prm(op, kSlotC) * (b.z * b.z + b.w * b.w);
    const REAL len = sqrt(b.w * b.w + b.z * b.z);
    const REAL inv = REAL(1) / (len != REAL(0) ? len : REAL(1));
    return REAL2(b.w, -b.z) * inv * magnitude * inv_m;
  }
  return REAL2(0);  // kOpGravityScaled: folded into (cx, cy)
}

// One coordinate wrapped periodically into [lo, hi] (World's wrap_coordinate).
REAL wrap(REAL v, REAL lo, REAL hi) {
  const REAL span = hi - lo;
  if (span <= REAL(0)) return v;
  if (v > hi) {
    v -= span;
    if (v > hi) v = lo + mod(v - lo, span);
  } else if (v < lo) {
    v += span;
    if (v < lo) v = hi - mod(hi - v, span);
  }
  return v;
}

// The boundary on body b (its radius r): the bounce (right before left,
// bottom before top; clamp, then reverse) or the periodic wrap.
REAL4 edges(REAL4 b, REAL r) {
  const uint f = p.boundary;
  const REAL rr = (f & kUseRadius) != 0u ? r : REAL(0);
  if ((f & kBounce) != 0u) {
    const bool right = (f & kRight) != 0u && b.x > p.width - rr;
    const bool left = (f & kLeft) != 0u && b.x < rr;
    const bool bottom = (f & kBottom) != 0u && b.y > p.height - rr;
    const bool top = (f & kTop) != 0u && b.y < rr;
    b.x = right ? p.width - rr : left ? rr : b.x;
    b.y = bottom ? p.height - rr : top ? rr : b.y;
    b.z = right || left ? b.z * p.reverse : b.z;
    b.w = bottom || top ? b.w * p.reverse : b.w;
  } else if ((f & kWrap) != 0u) {
    if ((f & (kLeft | kRight)) != 0u) b.x = wrap(b.x, -rr, p.width + rr);
    if ((f & (kTop | kBottom)) != 0u) b.y = wrap(b.y, -rr, p.height + rr);
  }
  return b;
}

void main() {
  const uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  const uint i = group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (group >= p.groups || i >= p.n) return;
  REAL4 b = state[i];
  const REAL4 q = props[i];
  REAL2 a = accel[i];
  const bool before = (p.boundary & kBefore) != 0u;
  for (uint s = 0u; s < p.steps; ++s) {
    a += REAL2(p.cx, p.cy);
    const uint step = p.first + s;
    if (kFixedOps >= 0) {
      if (kFixedOps > 0) a += op_accel(0, ivec4(kKind0, kFlags0, kWhich0, op_ints[0].w), step, b, q);
      if (kFixedOps > 1) a += op_accel(1, ivec4(kKind1, kFlags1, kWhich1, op_ints[1].w), step, b, q);
      if (kFixedOps > 2) a += op_accel(2, ivec4(kKind2, kFlags2, kWhich2, op_ints[2].w), step, b, q);
      if (kFixedOps > 3) a += op_accel(3, ivec4(kKind3, kFlags3, kWhich3, op_ints[3].w), step, b, q);
    } else {
      for (int op = 0; op < int(p.ops); ++op) a += op_accel(op, op_ints[op], step, b, q);
    }
    if (before) b = edges(b, q.y);
    b.zw += a * p.dt;
    b.xy += b.zw * p.dt;
    a = REAL2(0);
    if (!before) b = edges(b, q.y);
  }
  state[i] = b;
  accel[i] = REAL2(0);
  if (any(isnan(b)) || any(isinf(b))) atomicMin(first_bad, i);
}
