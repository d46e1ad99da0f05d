// SPDX-License-Identifier: MIT
// calder::math: deterministic sin, cos, atan, atan2, log and pow that give
// V8's Math results bit for bit (see calder/detmath.hpp).
//
// Sources of the algorithms and coefficients: fdlibm 5.3 (Copyright (C) 1993
// Sun Microsystems; netlib.org/fdlibm: k_sin.c, k_cos.c, e_rem_pio2.c,
// k_rem_pio2.c, s_atan.c, e_atan2.c, e_log.c, e_pow.c, s_scalbn.c) and its
// port in V8 (src/base/ieee754.cc), which Node's and Chrome's Math.sin, cos,
// atan2, log and pow run (Math.pow is V8's ieee754::legacy::pow). The code is
// written here; the polynomial coefficients are fdlibm's Remez fits and the
// constants are splits of pi/2, ln 2 and 1/ln 2 into exact pieces. Every
// operation is a plain IEEE double operation in a fixed order (calder compiles
// with -ffp-contract=off), and the words of a double are read and written
// through its 64-bit pattern, so the results do not depend on the platform.
//
// fdlibm's notice, as its licence asks (THIRD_PARTY.md):
//   Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved.
//   Developed at SunSoft, a Sun Microsystems, Inc. business.
//   Permission to use, copy, modify, and distribute this
//   software is freely granted, provided that this notice
//   is preserved.
#include "calder/detmath.hpp"

#include <cmath>  // floor, sqrt, fabs and copysign: exact in every C library
#include <cstdint>
#include <cstring>
#include <limits>

namespace calder::math {

namespace {

using i32 = std::int32_t;
using u32 = std::uint32_t;
using u64 = std::uint64_t;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// --- the words of a double (fdlibm's GET_HIGH_WORD, INSERT_WORDS, ...) ---

u64 to_bits(double x) {
  u64 u = 0;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
double from_bits(u64 u) {
  double x = 0.0;
  std::memcpy(&x, &u, sizeof x);
  return x;
}
i32 high_word(double x) { return static_cast<i32>(static_cast<u32>(to_bits(x) >> 32U)); }
u32 low_word(double x) { return static_cast<u32>(to_bits(x)); }
double from_words(u32 high, u32 low) { return from_bits((u64{high} << 32U) | low); }
double with_high_word(double x, u32 high) { return from_words(high, low_word(x)); }
double with_low_word(double x, u32 low) { return from_words(static_cast<u32>(high_word(x)), low); }
// v * 2^s for a possibly negative v, without signed-shift questions.
i32 shifted(i32 v, int s) { return static_cast<i32>(static_cast<u32>(v) << static_cast<u32>(s)); }

// x * 2^n, rounded once (fdlibm's scalbn).
double scale(double x, int n) {
  constexpr double two54 = 1.80143985094819840000e+16;   // 0x43500000 00000000
  constexpr double twom54 = 5.55111512312578270212e-17;  // 0x3C900000 00000000
  constexpr double huge = 1.0e+300;
  constexpr double tiny = 1.0e-300;
  i32 hx = high_word(x);
  int k = (hx & 0x7ff00000) >> 20;
  if (k == 0) {  // zero or subnormal
    if ((low_word(x) | static_cast<u32>(hx & 0x7fffffff)) == 0) return x;
    x *= two54;
    hx = high_word(x);
    k = ((hx & 0x7ff00000) >> 20) - 54;
    if (n < -50000) return tiny * x;
  }
  if (k == 0x7ff) return x + x;  // inf or NaN
  k += n;
  if (k > 0x7fe) return huge * std::copysign(huge, x);
  const u32 sign_and_mantissa = static_cast<u32>(hx) & 0x800fffffU;
  if (k > 0) return with_high_word(x, sign_and_mantissa | (static_cast<u32>(k) << 20U));
  if (k <= -54) {
    if (n > 50000) return huge * std::copysign(huge, x);
    return tiny * std::copysign(tiny, x);
  }
  k += 54;
  return with_high_word(x, sign_and_mantissa | (static_cast<u32>(k) << 20U)) * twom54;
}

// --- sin and cos on [-pi/4, pi/4]: x + y with y the tail of x ---

// sin(x + y); iy == 0 says y is zero.
double kernel_sin(double x, double y, int iy) {
  constexpr double S1 = -1.66666666666666324348e-01;  // 0xBFC55555 55555549
  constexpr double S2 = 8.33333333332248946124e-03;   // 0x3F811111 1110F8A6
  constexpr double S3 = -1.98412698298579493134e-04;  // 0xBF2A01A0 19C161D5
  constexpr double S4 = 2.75573137070700676789e-06;   // 0x3EC71DE3 57B1FE7D
  constexpr double S5 = -2.50507602534068634195e-08;  // 0xBE5AE5E6 8A2B9CEB
  constexpr double S6 = 1.58969099521155010221e-10;   // 0x3DE5D93A 5ACFD57C
  const i32 ix = high_word(x) & 0x7fffffff;
  if (ix < 0x3e400000 && static_cast<int>(x) == 0) return x;  // |x| < 2^-27
  const double z = x * x;
  const double v = z * x;
  const double r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
  if (iy == 0) return x + v * (S1 + z * r);
  return x - ((z * (0.5 * y - v * r) - y) - v * S1);
}

// cos(x + y).
double kernel_cos(double x, double y) {
  constexpr double C1 = 4.16666666666666019037e-02;   // 0x3FA55555 5555554C
  constexpr double C2 = -1.38888888888741095749e-03;  // 0xBF56C16C 16C15177
  constexpr double C3 = 2.48015872894767294178e-05;   // 0x3EFA01A0 19CB1590
  constexpr double C4 = -2.75573143513906633035e-07;  // 0xBE927E4F 809C52AD
  constexpr double C5 = 2.08757232129817482790e-09;   // 0x3E21EE9E BDB4B1C4
  constexpr double C6 = -1.13596475577881948265e-11;  // 0xBDA8FAE9 BE8838D4
  const i32 ix = high_word(x) & 0x7fffffff;
  if (ix < 0x3e400000 && static_cast<int>(x) == 0) return 1.0;  // |x| < 2^-27
  const double z = x * x;
  const double r = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
  if (ix < 0x3FD33333) return 1.0 - (0.5 * z - (z * r - x * y));  // |x| < 0.3
  // 1 - qx and z/2 - qx are exact: qx is |x|/4 cut to its high word, or
  // 0.28125 above 0.78125.
  const double qx = ix > 0x3fe90000 ? 0.28125 : from_words(static_cast<u32>(ix - 0x00200000), 0);
  const double hz = 0.5 * z - qx;
  const double a = 1.0 - qx;
  return a - (hz - (z * r - x * y));
}

// --- argument reduction: x = n pi/2 + (y0 + y1), |y0 + y1| <= pi/4 ---

// 2/pi in 24-bit pieces (1584 bits), for the reduction of huge arguments.
constexpr i32 kTwoOverPi[] = {
    0xA2F983, 0x6E4E44, 0x1529FC, 0x2757D1, 0xF534DD, 0xC0DB62, 0x95993C, 0x439041, 0xFE5163,
    0xABDEBB, 0xC561B7, 0x246E3A, 0x424DD2, 0xE00649, 0x2EEA09, 0xD1921C, 0xFE1DEB, 0x1CB129,
    0xA73EE8, 0x8235F5, 0x2EBB44, 0x84E99C, 0x7026B4, 0x5F7E41, 0x3991D6, 0x398353, 0x39F49C,
    0x845F8B, 0xBDF928, 0x3B1FF8, 0x97FFDE, 0x05980F, 0xEF2F11, 0x8B5A0A, 0x6D1F6D, 0x367ECF,
    0x27CB09, 0xB74F46, 0x3F669E, 0x5FEA2D, 0x7527BA, 0xC7EBE5, 0xF17B3D, 0x0739F7, 0x8A5292,
    0xEA6BFB, 0x5FB11F, 0x8D5D08, 0x560330, 0x46FC7B, 0x6BABF0, 0xCFBC20, 0x9AF436, 0x1DA9E3,
    0x91615E, 0xE61B08, 0x659985, 0x5F14A0, 0x68408D, 0xFFD880, 0x4D7327, 0x310606, 0x1556CA,
    0x73A8C9, 0x60E27B, 0xC08C6B,
};

// pi/2 in pieces of 24 bits (the first) and 24-bit steps, for the same.
constexpr double kPiOver2Pieces[] = {
    1.57079625129699707031e+00,  // 0x3FF921FB 40000000
    7.54978941586159635335e-08,  // 0x3E74442D 00000000
    5.39030252995776476554e-15,  // 0x3CF84698 80000000
    3.28200341580791294123e-22,  // 0x3B78CC51 60000000
    1.27065575308067607349e-29,  // 0x39F01B83 80000000
    1.22933308981111328932e-36,  // 0x387A2520 40000000
    2.73370053816464559624e-44,  // 0x36E38222 80000000
    2.16741683877804819444e-51,  // 0x3569F31D 00000000
};

constexpr double kTwo24 = 1.67772160000000000000e+07;   // 0x41700000 00000000
constexpr double kTwoM24 = 5.96046447753906250000e-08;  // 0x3E700000 00000000

// fdlibm's __kernel_rem_pio2 for 53-bit results (its prec 2): the digits of
// x * 2/pi from the 24-bit pieces tx[0..nx-1] of x / 2^e0, exact to well
// beyond the 53 bits kept.
class PayneHanek {
 public:
  PayneHanek(const double* tx, int nx, int e0) : jx_(nx - 1) {
    for (int i = 0; i < nx; ++i) x_[i] = tx[i];
    jv_ = (e0 - 3) / 24;
    if (jv_ < 0) jv_ = 0;
    q0_ = e0 - 24 * (jv_ + 1);
    int j = jv_ - jx_;
    for (int i = 0; i <= jx_ + kJk; ++i, ++j) f_[i] = j < 0 ? 0.0 : kTwoOverPi[j];
    for (int i = 0; i <= kJk; ++i) q_[i] = product_term(i);
  }

  // n mod 8 and y[0] + y[1] = the reduced argument.
  int reduce(double* y) {
    int jz = kJk;
    while (!distill(jz)) {
    }
    return finish(jz, y);
  }

 private:
  static constexpr int kJk = 4;  // fdlibm's init_jk for prec 2
  static constexpr int kJp = kJk;

  double product_term(int i) const {
    double fw = 0.0;
    for (int j = 0; j <= jx_; ++j) fw += x_[j] * f_[jx_ + i - j];
    return fw;
  }

  // One pass over q[0..jz]: iq, n, ih and the fraction z. False when the
  // fraction cancelled to zero and more terms of 2/pi are needed (jz grows).
  bool distill(int& jz) {
    z_ = q_[jz];
    for (int i = 0, j = jz; j > 0; ++i, --j) {
      const double fw = static_cast<double>(static_cast<i32>(kTwoM24 * z_));
      iq_[i] = static_cast<i32>(z_ - kTwo24 * fw);
      z_ = q_[j - 1] + fw;
    }
    z_ = scale(z_, q0_);
    z_ -= 8.0 * std::floor(z_ * 0.125);  // trim off the integer beyond 8
    n_ = static_cast<i32>(z_);
    z_ -= static_cast<double>(n_);
    ih_ = 0;
    if (q0_ > 0) {  // the integer part needs iq[jz-1] too
      const i32 i = iq_[jz - 1] >> (24 - q0_);
      n_ += i;
      iq_[jz - 1] -= shifted(i, 24 - q0_);
      ih_ = iq_[jz - 1] >> (23 - q0_);
    } else if (q0_ == 0) {
      ih_ = iq_[jz - 1] >> 23;
    } else if (z_ >= 0.5) {
      ih_ = 2;
    }
    if (ih_ > 0) round_up(jz);
    if (z_ != 0.0) return true;
    i32 any = 0;
    for (int i = jz - 1; i >= kJk; --i) any |= iq_[i];
    if (any != 0) return true;
    int k = 1;
    while (iq_[kJk - k] == 0) ++k;  // the terms that cancelled
    for (int i = jz + 1; i <= jz + k; ++i) {
      f_[jx_ + i] = kTwoOverPi[jv_ + i];
      q_[i] = product_term(i);
    }
    jz += k;
    return false;
  }

  // The fraction is >= 1/2: take 1 - fraction and count one more quadrant.
  void round_up(int jz) {
    n_ += 1;
    bool carry = false;
    for (int i = 0; i < jz; ++i) {
      const i32 j = iq_[i];
      if (!carry) {
        if (j != 0) {
          carry = true;
          iq_[i] = 0x1000000 - j;
        }
      } else {
        iq_[i] = 0xffffff - j;
      }
    }
    if (q0_ == 1) iq_[jz - 1] &= 0x7fffff;
    if (q0_ == 2) iq_[jz - 1] &= 0x3fffff;
    if (ih_ == 2) {
      z_ = 1.0 - z_;
      if (carry) z_ -= scale(1.0, q0_);
    }
  }

  // The fraction's digits times pi/2, summed into y[0] + y[1].
  int finish(int jz, double* y) {
    if (z_ == 0.0) {
      jz -= 1;
      q0_ -= 24;
      while (iq_[jz] == 0) {
        jz--;
        q0_ -= 24;
      }
    } else {
      z_ = scale(z_, -q0_);
      if (z_ >= kTwo24) {
        const double fw = static_cast<double>(static_cast<i32>(kTwoM24 * z_));
        iq_[jz] = static_cast<i32>(z_ - kTwo24 * fw);
        jz += 1;
        q0_ += 24;
        iq_[jz] = static_cast<i32>(fw);
      } else {
        iq_[jz] = static_cast<i32>(z_);
      }
    }
    double fw = scale(1.0, q0_);
    for (int i = jz; i >= 0; --i) {
      q_[i] = fw * static_cast<double>(iq_[i]);
      fw *= kTwoM24;
    }
    for (int i = jz; i >= 0; --i) {
      fw = 0.0;
      for (int k = 0; k <= kJp && k <= jz - i; ++k) fw += kPiOver2Pieces[k] * q_[i + k];
      fq_[jz - i] = fw;
    }
    fw = 0.0;
    for (int i = jz; i >= 0; --i) fw += fq_[i];
    y[0] = ih_ == 0 ? fw : -fw;
    fw = fq_[0] - fw;
    for (int i = 1; i <= jz; ++i) fw += fq_[i];
    y[1] = ih_ == 0 ? fw : -fw;
    return n_ & 7;
  }

  double x_[3] = {};
  int jx_;
  int jv_ = 0;
  int q0_ = 0;
  double f_[20] = {};
  double q_[20] = {};
  double fq_[20] = {};
  i32 iq_[20] = {};
  i32 n_ = 0;
  i32 ih_ = 0;
  double z_ = 0.0;
};

// The high words of n pi/2 for n = 1..32: near them the medium reduction
// needs more bits of pi/2.
constexpr i32 kNPiOver2High[] = {
    0x3FF921FB, 0x400921FB, 0x4012D97C, 0x401921FB, 0x401F6A7A, 0x4022D97C, 0x4025FDBB, 0x402921FB,
    0x402C463A, 0x402F6A7A, 0x4031475C, 0x4032D97C, 0x40346B9C, 0x4035FDBB, 0x40378FDB, 0x403921FB,
    0x403AB41B, 0x403C463A, 0x403DD85A, 0x403F6A7A, 0x40407E4C, 0x4041475C, 0x4042106C, 0x4042D97C,
    0x4043A28C, 0x40446B9C, 0x404534AC, 0x4045FDBB, 0x4046C6CB, 0x40478FDB, 0x404858EB, 0x404921FB,
};

// pi/2 as 33 + 33 + 33 + 53 bits.
constexpr double kPio2_1 = 1.57079632673412561417e+00;   // 0x3FF921FB 54400000
constexpr double kPio2_1t = 6.07710050650619224932e-11;  // 0x3DD0B461 1A626331
constexpr double kPio2_2 = 6.07710050630396597660e-11;   // 0x3DD0B461 1A600000
constexpr double kPio2_2t = 2.02226624879595063154e-21;  // 0x3BA3198A 2E037073
constexpr double kPio2_3 = 2.02226624871116645580e-21;   // 0x3BA3198A 2E000000
constexpr double kPio2_3t = 8.47842766036889956997e-32;  // 0x397B839A 252049C1

// |x| < 3pi/4: n = +-1, subtracting 33 + 53 bits of pi/2 (33 + 33 + 53 near pi/2).
int reduce_small(double x, i32 hx, i32 ix, double* y) {
  const double sign = hx > 0 ? 1.0 : -1.0;
  double z = x - sign * kPio2_1;
  if (ix != 0x3ff921fb) {
    y[0] = z - sign * kPio2_1t;
    y[1] = (z - y[0]) - sign * kPio2_1t;
  } else {
    z -= sign * kPio2_2;
    y[0] = z - sign * kPio2_2t;
    y[1] = (z - y[0]) - sign * kPio2_2t;
  }
  return hx > 0 ? 1 : -1;
}

// |x| <= 2^19 pi/2: n = round(|x| 2/pi), then |x| - n pi/2 with 33 + 53 bits
// of pi/2, and more where the first result lost too many bits.
int reduce_medium(double x, i32 hx, i32 ix, double* y) {
  constexpr double inv_pio2 = 6.36619772367581382433e-01;  // 0x3FE45F30 6DC9C883
  const double t = std::fabs(x);
  const i32 n = static_cast<i32>(t * inv_pio2 + 0.5);
  const double fn = static_cast<double>(n);
  double r = t - fn * kPio2_1;
  double w = fn * kPio2_1t;
  if (n < 32 && ix != kNPiOver2High[n - 1]) {
    y[0] = r - w;
  } else {
    const i32 j = ix >> 20;
    y[0] = r - w;
    i32 i = j - ((high_word(y[0]) >> 20) & 0x7ff);
    if (i > 16) {  // 2nd round: 118 bits
      double t2 = r;
      w = fn * kPio2_2;
      r = t2 - w;
      w = fn * kPio2_2t - ((t2 - r) - w);
      y[0] = r - w;
      i = j - ((high_word(y[0]) >> 20) & 0x7ff);
      if (i > 49) {  // 3rd round: 151 bits
        t2 = r;
        w = fn * kPio2_3;
        r = t2 - w;
        w = fn * kPio2_3t - ((t2 - r) - w);
        y[0] = r - w;
      }
    }
  }
  y[1] = (r - y[0]) - w;
  if (hx < 0) {
    y[0] = -y[0];
    y[1] = -y[1];
    return -n;
  }
  return n;
}

// x = n pi/2 + y[0] + y[1] for |x| > pi/4 (fdlibm's __ieee754_rem_pio2).
int rem_pio2(double x, double* y) {
  const i32 hx = high_word(x);
  const i32 ix = hx & 0x7fffffff;
  if (ix < 0x4002d97c) return reduce_small(x, hx, ix, y);
  if (ix <= 0x413921fb) return reduce_medium(x, hx, ix, y);
  if (ix >= 0x7ff00000) {  // inf or NaN
    y[0] = y[1] = x - x;
    return 0;
  }
  // |x| = z 2^e0 with z in [2^23, 2^24), cut into three 24-bit pieces.
  const i32 e0 = (ix >> 20) - 1046;
  double z = from_words(static_cast<u32>(ix - shifted(e0, 20)), low_word(x));
  double tx[3];
  for (int i = 0; i < 2; ++i) {
    tx[i] = static_cast<double>(static_cast<i32>(z));
    z = (z - tx[i]) * kTwo24;
  }
  tx[2] = z;
  int nx = 3;
  while (tx[nx - 1] == 0.0) nx--;
  const int n = PayneHanek(tx, nx, e0).reduce(y);
  if (hx < 0) {
    y[0] = -y[0];
    y[1] = -y[1];
    return -n;
  }
  return n;
}

}  // namespace

double sin(double x) {
  const i32 ix = high_word(x) & 0x7fffffff;
  if (ix <= 0x3fe921fb) return kernel_sin(x, 0.0, 0);  // |x| <= pi/4
  if (ix >= 0x7ff00000) return x - x;                  // inf or NaN
  double y[2];
  switch (rem_pio2(x, y) & 3) {
    case 0:
      return kernel_sin(y[0], y[1], 1);
    case 1:
      return kernel_cos(y[0], y[1]);
    case 2:
      return -kernel_sin(y[0], y[1], 1);
    default:
      return -kernel_cos(y[0], y[1]);
  }
}

double cos(double x) {
  const i32 ix = high_word(x) & 0x7fffffff;
  if (ix <= 0x3fe921fb) return kernel_cos(x, 0.0);  // |x| <= pi/4
  if (ix >= 0x7ff00000) return x - x;               // inf or NaN
  double y[2];
  switch (rem_pio2(x, y) & 3) {
    case 0:
      return kernel_cos(y[0], y[1]);
    case 1:
      return -kernel_sin(y[0], y[1], 1);
    case 2:
      return -kernel_cos(y[0], y[1]);
    default:
      return kernel_sin(y[0], y[1], 1);
  }
}

// atan: reduced to [0, 7/16] through atan(x) = atan(c) + atan((x - c)/(1 + x c))
// for c = 1/2, 1, 3/2 and atan(x) = pi/2 - atan(1/x), then an odd polynomial.
double atan(double x) {
  constexpr double atan_hi[] = {
      4.63647609000806093515e-01,  // atan(0.5) hi 0x3FDDAC67 0561BB4F
      7.85398163397448278999e-01,  // atan(1.0) hi 0x3FE921FB 54442D18
      9.82793723247329054082e-01,  // atan(1.5) hi 0x3FEF730B D281F69B
      1.57079632679489655800e+00,  // atan(inf) hi 0x3FF921FB 54442D18
  };
  constexpr double atan_lo[] = {
      2.26987774529616870924e-17,  // atan(0.5) lo 0x3C7A2B7F 222F65E2
      3.06161699786838301793e-17,  // atan(1.0) lo 0x3C81A626 33145C07
      1.39033110312309984516e-17,  // atan(1.5) lo 0x3C700788 7AF0CBBD
      6.12323399573676603587e-17,  // atan(inf) lo 0x3C91A626 33145C07
  };
  constexpr double aT[] = {
      3.33333333333329318027e-01,  -1.99999999998764832476e-01, 1.42857142725034663711e-01,
      -1.11111104054623557880e-01, 9.09088713343650656196e-02,  -7.69187620504482999495e-02,
      6.66107313738753120669e-02,  -5.83357013379057348645e-02, 4.97687799461593236017e-02,
      -3.65315727442169155270e-02, 1.62858201153657823623e-02,
  };
  const i32 hx = high_word(x);
  const i32 ix = hx & 0x7fffffff;
  if (ix >= 0x44100000) {                                                         // |x| >= 2^66
    if (ix > 0x7ff00000 || (ix == 0x7ff00000 && low_word(x) != 0)) return x + x;  // NaN
    return hx > 0 ? atan_hi[3] + atan_lo[3] : -atan_hi[3] - atan_lo[3];
  }
  int id = -1;
  if (ix < 0x3fdc0000) {            // |x| < 0.4375
    if (ix < 0x3e400000) return x;  // |x| < 2^-27
  } else {
    x = std::fabs(x);
    if (ix < 0x3ff30000) {    // |x| < 1.1875
      if (ix < 0x3fe60000) {  // 7/16 <= |x| < 11/16
        id = 0;
        x = (2.0 * x - 1.0) / (2.0 + x);
      } else {  // 11/16 <= |x| < 19/16
        id = 1;
        x = (x - 1.0) / (x + 1.0);
      }
    } else if (ix < 0x40038000) {  // |x| < 2.4375
      id = 2;
      x = (x - 1.5) / (1.0 + 1.5 * x);
    } else {  // 2.4375 <= |x| < 2^66
      id = 3;
      x = -1.0 / x;
    }
  }
  const double z = x * x;
  const double w = z * z;
  // The odd and even halves of sum aT[i] z^(i+1).
  const double s1 =
      z * (aT[0] + w * (aT[2] + w * (aT[4] + w * (aT[6] + w * (aT[8] + w * aT[10])))));
  const double s2 = w * (aT[1] + w * (aT[3] + w * (aT[5] + w * (aT[7] + w * aT[9]))));
  if (id < 0) return x - x * (s1 + s2);
  const double r = atan_hi[id] - ((x * (s1 + s2) - atan_lo[id]) - x);
  return hx < 0 ? -r : r;
}

double atan2(double y, double x) {
  constexpr double pi_o_4 = 7.8539816339744827900e-01;  // 0x3FE921FB 54442D18
  constexpr double pi_o_2 = 1.5707963267948965580e+00;  // 0x3FF921FB 54442D18
  constexpr double pi = 3.1415926535897931160e+00;      // 0x400921FB 54442D18
  constexpr double pi_lo = 1.2246467991473531772e-16;   // 0x3CA1A626 33145C07
  const i32 hx = high_word(x);
  const i32 hy = high_word(y);
  const u32 lx = low_word(x);
  const u32 ly = low_word(y);
  const i32 ix = hx & 0x7fffffff;
  const i32 iy = hy & 0x7fffffff;
  if ((ix | (lx != 0 ? 1 : 0)) > 0x7ff00000 || (iy | (ly != 0 ? 1 : 0)) > 0x7ff00000) {
    return x + y;  // NaN
  }
  if (hx == 0x3ff00000 && lx == 0) return atan(y);  // x = 1
  // 2 * (x < 0) + (y < 0): the quadrant.
  const int m = ((hy < 0) ? 1 : 0) | ((hx < 0) ? 2 : 0);
  const double sign_y = hy < 0 ? -1.0 : 1.0;
  if ((static_cast<u32>(iy) | ly) == 0) {  // y = +-0
    if (m < 2) return y;
    return sign_y * pi;
  }
  if ((static_cast<u32>(ix) | lx) == 0) return sign_y * pi_o_2;  // x = +-0
  if (ix == 0x7ff00000) {                                        // x = +-inf
    if (iy == 0x7ff00000) return sign_y * ((m & 2) != 0 ? 3.0 * pi_o_4 : pi_o_4);
    return (m & 2) != 0 ? sign_y * pi : sign_y * 0.0;
  }
  if (iy == 0x7ff00000) return sign_y * pi_o_2;  // y = +-inf
  const i32 k = (iy - ix) >> 20;
  double z = 0.0;
  int quadrant = m;
  if (k > 60) {  // |y/x| > 2^60
    z = pi_o_2 + 0.5 * pi_lo;
    quadrant &= 1;
  } else if (hx < 0 && k < -60) {  // 0 > |y|/x > -2^-60
    z = 0.0;
  } else {
    z = atan(std::fabs(y / x));
  }
  switch (quadrant) {
    case 0:
      return z;
    case 1:
      return -z;
    case 2:
      return pi - (z - pi_lo);
    default:
      return (z - pi_lo) - pi;
  }
}

// log: x = 2^k (1 + f) with sqrt(2)/2 < 1 + f < sqrt(2); log(1 + f) = 2s +
// s R(s^2) with s = f / (2 + f) (R: fdlibm's Remez fit), plus k ln 2 in two
// pieces.
double log(double x) {
  constexpr double ln2_hi = 6.93147180369123816490e-01;  // 0x3FE62E42 FEE00000
  constexpr double ln2_lo = 1.90821492927058770002e-10;  // 0x3DEA39EF 35793C76
  constexpr double two54 = 1.80143985094819840000e+16;   // 0x43500000 00000000
  constexpr double Lg1 = 6.666666666666735130e-01;       // 0x3FE55555 55555593
  constexpr double Lg2 = 3.999999999940941908e-01;       // 0x3FD99999 9997FA04
  constexpr double Lg3 = 2.857142874366239149e-01;       // 0x3FD24924 94229359
  constexpr double Lg4 = 2.222219843214978396e-01;       // 0x3FCC71C5 1D8E78AF
  constexpr double Lg5 = 1.818357216161805012e-01;       // 0x3FC74664 96CB03DE
  constexpr double Lg6 = 1.531383769920937332e-01;       // 0x3FC39A09 D078C69F
  constexpr double Lg7 = 1.479819860511658591e-01;       // 0x3FC2F112 DF3E5244
  i32 hx = high_word(x);
  const u32 lx = low_word(x);
  int k = 0;
  if (hx < 0x00100000) {  // x < 2^-1022
    if ((static_cast<u32>(hx & 0x7fffffff) | lx) == 0)
      return -std::numeric_limits<double>::infinity();
    if (hx < 0) return kNaN;  // log(-#) = NaN
    k -= 54;                  // subnormal: scale up
    x *= two54;
    hx = high_word(x);
  }
  if (hx >= 0x7ff00000) return x + x;  // inf or NaN
  k += (hx >> 20) - 1023;
  hx &= 0x000fffff;
  const i32 i = (hx + 0x95f64) & 0x100000;
  x = with_high_word(x, static_cast<u32>(hx | (i ^ 0x3ff00000)));  // x or x/2
  k += (i >> 20);
  const double f = x - 1.0;
  const double dk = static_cast<double>(k);
  if ((0x000fffff & (2 + hx)) < 3) {  // -2^-20 <= f < 2^-20
    if (f == 0.0) return k == 0 ? 0.0 : dk * ln2_hi + dk * ln2_lo;
    const double R = f * f * (0.5 - 0.33333333333333333 * f);
    if (k == 0) return f - R;
    return dk * ln2_hi - ((R - dk * ln2_lo) - f);
  }
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double w = z * z;
  const double t1 = w * (Lg2 + w * (Lg4 + w * Lg6));
  const double t2 = z * (Lg1 + w * (Lg3 + w * (Lg5 + w * Lg7)));
  const double R = t2 + t1;
  if (((hx - 0x6147a) | (0x6b851 - hx)) > 0) {  // f beyond about 0.1 from 1
    const double hfsq = 0.5 * f * f;
    if (k == 0) return f - (hfsq - s * (hfsq + R));
    return dk * ln2_hi - ((hfsq - (s * (hfsq + R) + dk * ln2_lo)) - f);
  }
  if (k == 0) return f - s * (f - R);
  return dk * ln2_hi - ((s * (f - R) - dk * ln2_lo) - f);
}

namespace {

// For x < 0: 0 if y is not an integer, 1 if it is odd, 2 if even.
int integer_kind(i32 iy, u32 ly) {
  if (iy >= 0x43400000) return 2;  // |y| >= 2^53: even
  if (iy < 0x3ff00000) return 0;   // |y| < 1
  const int k = (iy >> 20) - 0x3ff;
  if (k > 20) {
    const u32 j = ly >> static_cast<u32>(52 - k);
    if ((j << static_cast<u32>(52 - k)) == ly) return 2 - static_cast<int>(j & 1U);
  } else if (ly == 0) {
    const i32 j = iy >> (20 - k);
    if (shifted(j, 20 - k) == iy) return 2 - static_cast<int>(j & 1);
  }
  return 0;
}

// pow's special values of y and x (fdlibm's and JavaScript's): true with the
// result in out, false when the general method applies.
bool pow_special(double x, double y, int yisint, double& out) {
  const i32 hx = high_word(x);
  const i32 hy = high_word(y);
  const u32 lx = low_word(x);
  const i32 ix = hx & 0x7fffffff;
  const i32 iy = hy & 0x7fffffff;
  if (low_word(y) == 0) {
    if (iy == 0x7ff00000) {  // y = +-inf
      if ((static_cast<u32>(ix - 0x3ff00000) | lx) == 0) {
        out = y - y;  // (+-1)^(+-inf) is NaN in JavaScript
      } else if (ix >= 0x3ff00000) {
        out = hy >= 0 ? y : 0.0;  // (|x| > 1)^(+-inf) = inf, 0
      } else {
        out = hy < 0 ? -y : 0.0;  // (|x| < 1)^(+-inf) = 0, inf
      }
      return true;
    }
    if (iy == 0x3ff00000) {  // y = +-1
      out = hy < 0 ? 1.0 / x : x;
      return true;
    }
    if (hy == 0x40000000) {  // y = 2
      out = x * x;
      return true;
    }
    if (hy == 0x3fe00000 && hx >= 0) {  // y = 0.5, x >= +0
      out = std::sqrt(x);
      return true;
    }
  }
  if (lx == 0 && (ix == 0x7ff00000 || ix == 0 || ix == 0x3ff00000)) {  // x = +-0, +-inf, +-1
    double z = std::fabs(x);
    if (hy < 0) z = 1.0 / z;
    if (hx < 0) {
      if ((static_cast<u32>(ix - 0x3ff00000) | static_cast<u32>(yisint)) == 0) {
        z = kNaN;  // (-1)^non-integer
      } else if (yisint == 1) {
        z = -z;  // (x < 0)^odd = -(|x|^odd)
      }
    }
    out = z;
    return true;
  }
  return false;
}

// log2|x| = t1 + t2 (t1 with its low word zero) for x within 2^-20 of 1.
void log2_near_one(double ax, double& t1, double& t2) {
  constexpr double ivln2 = 1.44269504088896338700e+00;    // 0x3FF71547 652B82FE
  constexpr double ivln2_h = 1.44269502162933349609e+00;  // 0x3FF71547 60000000
  constexpr double ivln2_l = 1.92596299112661746887e-08;  // 0x3E54AE0B F85DDF44
  const double t = ax - 1.0;                              // 20 trailing zeros
  const double w = (t * t) * (0.5 - t * (0.3333333333333333333333 - t * 0.25));
  const double u = ivln2_h * t;
  const double v = t * ivln2_l - w * ivln2;
  t1 = with_low_word(u + v, 0);
  t2 = v - (t1 - u);
}

// log2|x| = t1 + t2 (t1 with its low word zero), to about 2^-64 relative.
void log2_split(double ax, double& t1, double& t2) {
  constexpr double two53 = 9007199254740992.0;
  constexpr double dp_h[] = {0.0, 5.84962487220764160156e-01};  // 0x3FE2B803 40000000
  constexpr double dp_l[] = {0.0, 1.35003920212974897128e-08};  // 0x3E4CFDEB 43CFD006
  constexpr double L1 = 5.99999999999994648725e-01;             // 0x3FE33333 33333303
  constexpr double L2 = 4.28571428578550184252e-01;             // 0x3FDB6DB6 DB6FABFF
  constexpr double L3 = 3.33333329818377432918e-01;             // 0x3FD55555 518F264D
  constexpr double L4 = 2.72728123808534006489e-01;             // 0x3FD17460 A91D4101
  constexpr double L5 = 2.30660745775561754067e-01;             // 0x3FCD864A 93C9DB65
  constexpr double L6 = 2.06975017800338417784e-01;             // 0x3FCA7E28 4A454EEF
  constexpr double cp = 9.61796693925975554329e-01;             // 2/(3 ln 2)
  constexpr double cp_h = 9.61796700954437255859e-01;           // 0x3FEEC709 E0000000
  constexpr double cp_l = -7.02846165095275826516e-09;          // 0xBE3E2FE0 145B01F5
  int n = 0;
  i32 ix = high_word(ax);
  if (ix < 0x00100000) {  // subnormal
    ax *= two53;
    n -= 53;
    ix = high_word(ax);
  }
  n += (ix >> 20) - 0x3ff;
  const i32 j = ix & 0x000fffff;
  ix = j | 0x3ff00000;  // normalised to [1, 2)
  int k = 0;
  if (j <= 0x3988E) {
    k = 0;  // |x| < sqrt(3/2)
  } else if (j < 0xBB67A) {
    k = 1;  // |x| < sqrt(3)
  } else {
    n += 1;
    ix -= 0x00100000;
  }
  ax = with_high_word(ax, static_cast<u32>(ix));
  const double bp = k == 0 ? 1.0 : 1.5;
  // ss = s_h + s_l = (x - 1)/(x + 1) or (x - 1.5)/(x + 1.5)
  double u = ax - bp;
  double v = 1.0 / (ax + bp);
  const double ss = u * v;
  const double s_h = with_low_word(ss, 0);
  double t_h = from_words(static_cast<u32>(((ix >> 1) | 0x20000000) + 0x00080000 + (k << 18)), 0);
  double t_l = ax - (t_h - bp);
  const double s_l = v * ((u - s_h * t_h) - s_h * t_l);
  // log(ax)
  double s2 = ss * ss;
  double r = s2 * s2 * (L1 + s2 * (L2 + s2 * (L3 + s2 * (L4 + s2 * (L5 + s2 * L6)))));
  r += s_l * (s_h + ss);
  s2 = s_h * s_h;
  t_h = with_low_word(3.0 + s2 + r, 0);
  t_l = r - ((t_h - 3.0) - s2);
  u = s_h * t_h;  // u + v = ss (1 + ...)
  v = s_l * t_h + t_l * ss;
  const double p_h = with_low_word(u + v, 0);
  const double p_l = v - (p_h - u);
  const double z_h = cp_h * p_h;  // cp_h + cp_l = 2/(3 ln 2)
  const double z_l = cp_l * p_h + p_l * cp + dp_l[k];
  // log2(ax) = (ss + ...) 2/(3 ln 2) = n + dp_h + z_h + z_l
  const double t = static_cast<double>(n);
  t1 = with_low_word(((z_h + z_l) + dp_h[k]) + t, 0);
  t2 = z_l - (((t1 - t) - dp_h[k]) - z_h);
}

// s 2^((y1 + y2)(t1 + t2)), y = y1 + y2 split like t1 + t2.
double pow_exp2(double y, double t1, double t2, double s) {
  constexpr double huge = 1.0e300;
  constexpr double tiny = 1.0e-300;
  constexpr double ovt = 8.0085662595372944372e-0017;    // -(1024 - log2(ovfl + 0.5 ulp))
  constexpr double P1 = 1.66666666666666019037e-01;      // 0x3FC55555 5555553E
  constexpr double P2 = -2.77777777770155933842e-03;     // 0xBF66C16C 16BEBD93
  constexpr double P3 = 6.61375632143793436117e-05;      // 0x3F11566A AF25DE2C
  constexpr double P4 = -1.65339022054652515390e-06;     // 0xBEBBBD41 C5D26BF1
  constexpr double P5 = 4.13813679705723846039e-08;      // 0x3E663769 72BEA4D0
  constexpr double lg2 = 6.93147180559945286227e-01;     // 0x3FE62E42 FEFA39EF
  constexpr double lg2_h = 6.93147182464599609375e-01;   // 0x3FE62E43 00000000
  constexpr double lg2_l = -1.90465429995776804525e-09;  // 0xBE205C61 0CA86C39
  const double y1 = with_low_word(y, 0);
  const double p_l = (y - y1) * t1 + y * t2;
  double p_h = y1 * t1;
  double z = p_l + p_h;
  i32 j = high_word(z);
  const u32 lz = low_word(z);
  if (j >= 0x40900000) {  // z >= 1024
    if ((static_cast<u32>(j - 0x40900000) | lz) != 0) return s * huge * huge;
    if (p_l + ovt > z - p_h) return s * huge * huge;
  } else if ((j & 0x7fffffff) >= 0x4090cc00) {  // z <= -1075
    if (((static_cast<u32>(j) - 0xc090cc00U) | lz) != 0) return s * tiny * tiny;
    if (p_l <= z - p_h) return s * tiny * tiny;
  }
  // 2^(p_h + p_l) = 2^n 2^r, n = [z + 0.5]
  const i32 i = j & 0x7fffffff;
  i32 k = (i >> 20) - 0x3ff;
  i32 n = 0;
  if (i > 0x3fe00000) {
    n = j + (0x00100000 >> (k + 1));
    k = ((n & 0x7fffffff) >> 20) - 0x3ff;  // the new k for n
    const double t = from_words(static_cast<u32>(n & ~(0x000fffff >> k)), 0);
    n = ((n & 0x000fffff) | 0x00100000) >> (20 - k);
    if (j < 0) n = -n;
    p_h -= t;
  }
  double t = with_low_word(p_l + p_h, 0);
  const double u = t * lg2_h;
  const double v = (p_l - (t - p_h)) * lg2 + t * lg2_l;
  z = u + v;
  const double w = v - (z - u);
  t = z * z;
  const double tt = z - t * (P1 + t * (P2 + t * (P3 + t * (P4 + t * P5))));
  const double r = (z * tt) / ((tt - 2.0) - (w + z * w));
  z = 1.0 - (r - z);
  j = high_word(z) + shifted(n, 20);
  if ((j >> 20) <= 0) {
    z = scale(z, n);  // subnormal result
  } else {
    z = with_high_word(z, static_cast<u32>(high_word(z) + shifted(n, 20)));
  }
  return s * z;
}

}  // namespace

// pow: log2|x| to about 64 bits as t1 + t2, y log2|x| = n + y' exactly
// enough, then 2^n exp(y' ln 2).
double pow(double x, double y) {
  constexpr double huge = 1.0e300;
  constexpr double tiny = 1.0e-300;
  const i32 hx = high_word(x);
  const i32 hy = high_word(y);
  const u32 lx = low_word(x);
  const u32 ly = low_word(y);
  const i32 ix = hx & 0x7fffffff;
  const i32 iy = hy & 0x7fffffff;
  if ((static_cast<u32>(iy) | ly) == 0) return 1.0;  // x^0 = 1, even for NaN
  if (ix > 0x7ff00000 || (ix == 0x7ff00000 && lx != 0) || iy > 0x7ff00000 ||
      (iy == 0x7ff00000 && ly != 0)) {
    return x + y;  // NaN
  }
  const int yisint = hx < 0 ? integer_kind(iy, ly) : 0;
  double special = 0.0;
  if (pow_special(x, y, yisint, special)) return special;
  if (hx < 0 && yisint == 0) return kNaN;               // (x < 0)^non-integer
  const double s = hx < 0 && yisint == 1 ? -1.0 : 1.0;  // (x < 0)^odd is negative
  double t1 = 0.0;
  double t2 = 0.0;
  if (iy > 0x41e00000) {    // |y| > 2^31
    if (iy > 0x43f00000) {  // |y| > 2^64: must overflow or underflow
      if (ix <= 0x3fefffff) return hy < 0 ? huge * huge : tiny * tiny;
      if (ix >= 0x3ff00000) return hy > 0 ? huge * huge : tiny * tiny;
    }
    // over/underflow unless x is close to 1
    if (ix < 0x3fefffff) return hy < 0 ? s * huge * huge : s * tiny * tiny;
    if (ix > 0x3ff00000) return hy > 0 ? s * huge * huge : s * tiny * tiny;
    log2_near_one(std::fabs(x), t1, t2);
  } else {
    log2_split(std::fabs(x), t1, t2);
  }
  return pow_exp2(y, t1, t2, s);
}

}  // namespace calder::math
