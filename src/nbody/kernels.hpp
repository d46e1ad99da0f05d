// SPDX-License-Identifier: MIT
// calder::nbody internals: the pair-sum kernels, compiled once per instruction
// set (src/nbody/kernels.cpp) and chosen at run time (dispatch.cpp).
//
// A kernel adds, for each target t of a contiguous block, the sum over the
// sources s (in source order, always the same for a given target)
//
//     sum_s  m_s (p_s - p_t) w(|p_s - p_t|)
//
// to (out_x[t], out_y[t]), where w is the law's weight without G:
//
//     plummer                 w = 1 / (r^2 + eps^2)^(3/2)
//     clamp_distance          w = 1 / (r d^2),  d = clamp(r, lo, hi)
//     clamp_squared_distance  w = 1 / (r q),    q = clamp(r^2, lo, hi)
//
// and w = 0 where p_s == p_t (a body on itself, coincident bodies) for the
// clamped laws and for plummer with eps = 0. The pair kernels (Pairs64,
// Pairs32) take each pair of two disjoint sets once and add it to both
// bodies' sums, m_s w to the target's and m_t w (with -(p_s - p_t)) to the
// source's: direct summation's larger systems (src/nbody/direct.cpp).
#pragma once

#include <cstddef>

#include "calder/nbody.hpp"

namespace calder::nbody::detail {

// The law's parameters in both precisions (float ones already scaled to the
// float32 kernel's units by the caller).
struct LawParams {
  Law law = Law::plummer;
  double eps2 = 0.0;  // softening^2 (plummer)
  double lo = 0.0;    // clamp bounds: distance, or squared distance
  double hi = 0.0;
  // float64, plummer: every pair's r^2 = dx^2 + dy^2 + eps2 lies in float's
  // normal range, so that kernels without a double estimate may start from
  // float's (float_range_of).
  bool float_range = false;
  float eps2_f = 0.0f;
  float lo_f = 0.0f;
  float hi_f = 0.0f;
};

// Whether r^2 = dx^2 + dy^2 + eps2 lies within 2^-120 .. 2^122, in float's
// normal range, for every pair of bodies whose coordinates differ by at most
// `span` (the bounding box's largest side).
inline bool float_range_of(double span, double eps2) {
  return eps2 >= 0x1p-120 && eps2 <= 0x1p120 && span < 0x1p60;
}

template <typename T>
struct Bodies {
  const T* x = nullptr;
  const T* y = nullptr;
  const T* m = nullptr;
  std::size_t n = 0;
  // float32 only, optional: the low parts of two-float positions (x + x_lo
  // is the position to ~2^-48 relative). With them the kernel forms each
  // difference as (x_j - x_i) + (x_lo_j - x_lo_i): exact to float's
  // precision however close the pair, the hi difference being exact for
  // close pairs (Sterbenz) and the low parts supplying the bits float lost.
  const T* x_lo = nullptr;
  const T* y_lo = nullptr;

  // Bodies [from, from + count) of these.
  Bodies slice(std::size_t from, std::size_t count) const {
    Bodies s = *this;
    s.x += from;
    s.y += from;
    s.m += from;
    if (x_lo != nullptr) s.x_lo += from;
    if (y_lo != nullptr) s.y_lo += from;
    s.n = count;
    return s;
  }
};

// Tree nodes as sources for the multipole kernels: centre of mass, mass and,
// pre-multiplied, the moments about the centre of mass (s = body - centre):
//   q3xx, q3xy, q3yy = 3 Q,  Q = sum m s s^T          (second moments)
//   t15 = 1.5 tr Q
//   o_xxx, o_xxy, o_xyy, o_yyy = 7.5 O,  O = sum m s s s  (third moments)
//   p_x, p_y = 1.5 P,  P = sum m s |s|^2
//   h_xxxx, ..., h_yyyy = 17.5 H,  H = sum m s s s s        (fourth moments)
//   g_xx, g_xy, g_yy = 7.5 G,  G = sum m s s^T |s|^2  (H's trace)
//   tt = 1.875 tr G
template <typename T>
struct Nodes {
  static constexpr std::size_t kColumns = 22;
  // x, y, m, q3xx, q3xy, q3yy, t15, o_xxx, o_xxy, o_xyy, o_yyy, p_x, p_y,
  // h_xxxx, h_xxxy, h_xxyy, h_xyyy, h_yyyy, g_xx, g_xy, g_yy, tt
  const T* column[kColumns] = {};
  std::size_t n = 0;
};

// Targets (tx, ty)[0, nt) against all sources; sums added to out_x, out_y.
using Accumulate64 = void (*)(const double* tx, const double* ty, std::size_t nt,
                              const Bodies<double>& sources, const LawParams& law, double* out_x,
                              double* out_y);
// The same in float32: each target's sum is accumulated in float over tiles
// of kFloatTile consecutive sources, and the tile sums in double. Two-float
// positions when the targets' (tx_lo, ty_lo) and the sources' low parts are
// given (all four), plain floats otherwise.
using Accumulate32 = void (*)(const float* tx, const float* ty, const float* tx_lo,
                              const float* ty_lo, std::size_t nt, const Bodies<float>& sources,
                              const LawParams& law, double* out_x, double* out_y);

// The multipole expansion of each node's Plummer-softened field (always
// Law::plummer) to fourth order, with d = node - target, R^2 = |d|^2 + eps^2:
//     m d/R^3                                                    (monopole)
//   - 3 Q d/R^5 + (15/2)(d.Q d) d/R^7 - (3/2) tr(Q) d/R^5      (quadrupole)
//   + (15/2) O(d,d,.)/R^7 - (35/2) O(d,d,d) d/R^9
//   - (3/2) P/R^5 + (15/2)(P.d) d/R^7                           (octupole)
//   - (35/2) H(d,d,d,.)/R^9 + (315/8) H(d,d,d,d) d/R^11
//   + (15/2) G d/R^7 - (105/4)(d.G d) d/R^9 + (15/8) tr(G) d/R^7
//                                                          (hexadecapole)
// (the terms of -(1/k!) M_k . grad^(k+1) of 1/R, M_k the k-th moments; a
// cell of evenly spread bodies has a small octupole but not a small
// hexadecapole, so the fourth order is what lets theta grow).
using AccumulateMultipole64 = void (*)(const double* tx, const double* ty, std::size_t nt,
                                       const Nodes<double>& nodes, const LawParams& law,
                                       double* out_x, double* out_y);
using AccumulateMultipole32 = void (*)(const float* tx, const float* ty, std::size_t nt,
                                       const Nodes<float>& nodes, const LawParams& law,
                                       double* out_x, double* out_y);

// Pairs between two disjoint sets of bodies a and b, each pair once: adds
// a's sums over b to (a_x, a_y) and b's sums over a to (b_x, b_y). a.n and
// b.n are whole vectors (the group blocks' lane counts) and at most
// kFloatTile; float32 sums run in float and are added in double.
using Pairs64 = void (*)(const Bodies<double>& a, const Bodies<double>& b, const LawParams& law,
                         double* a_x, double* a_y, double* b_x, double* b_y);
using Pairs32 = void (*)(const Bodies<float>& a, const Bodies<float>& b, const LawParams& law,
                         double* a_x, double* a_y, double* b_x, double* b_y);

inline constexpr std::size_t kFloatTile = 512;

// Barnes-Hut's far field of a group: its values (fx, fy)[i * kFarStencil + j]
// at the points (cx + half u_i, cy + half u_j) of the group's square, u the
// Chebyshev points on [-1, 1] (`nodes`) with the Lagrange basis' weights
// 1 / prod_{j != i} (u_i - u_j) (`weights`), interpolated at each target by
// the tensor product of the Lagrange polynomials of degree kFarStencil - 1.
inline constexpr std::size_t kFarStencil = 4;
struct FarField {
  double cx, cy, inv_half;
  const double* nodes;    // kFarStencil
  const double* weights;  // kFarStencil
  const double* fx;       // kFarStencil^2
  const double* fy;
};
// The far field at targets (tx, ty)[0, nt), added to out_x, out_y.
using InterpolateFar = void (*)(const double* tx, const double* ty, std::size_t nt,
                                const FarField& far, double* out_x, double* out_y);

struct KernelTable {
  const char* name;           // e.g. "avx512", "avx2+fma", "sse2", "generic"
  std::size_t block64;        // targets per register block of the direct kernels, float64
  std::size_t block32;        // and float32
  Accumulate64 accumulate64;  // wide register blocks (direct summation)
  Accumulate32 accumulate32;
  std::size_t group_block64;  // one vector of targets (Barnes-Hut groups pad at most one)
  std::size_t group_block32;
  Accumulate64 group64;
  Accumulate32 group32;
  AccumulateMultipole64 multipole64;
  AccumulateMultipole32 multipole32;
  // Barnes-Hut, float64: the default of BarnesHutOptions::target_block.
  std::size_t target_block64;
  InterpolateFar interpolate_far;
  Pairs64 pairs64;  // direct summation, each pair once (Newton's third law)
  Pairs32 pairs32;
};

// The kernels for the instruction set the running CPU supports best among
// those compiled in; chosen once.
const KernelTable& kernels();

}  // namespace calder::nbody::detail
