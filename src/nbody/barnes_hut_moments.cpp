// SPDX-License-Identifier: MIT
// Barnes-Hut, the multipole terms: each node's mass and moments as the
// multipole kernels read them (kernels.hpp: m, 3 Q, 1.5 tr Q, 7.5 O, 1.5 P,
// P = sum m s |s|^2), in float64 or scaled into the float32 frame, and the
// bodies' masses for float32.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "barnes_hut_tree.hpp"
#include "common.hpp"

namespace calder::nbody {

namespace {

// The kernel's kMoments numbers for one node's moments, scaled by powers of
// the frame's length and mass scales (1 for float64).
struct MomentScales {
  double mass = 1.0;
  double second = 1.0;  // length^2 mass
  double third = 1.0;   // length^3 mass
  double fourth = 1.0;  // length^4 mass
};

template <typename T>
void write_moments(const bh::Moments& m, const MomentScales& s, T* o) {
  o[0] = static_cast<T>(m.mass * s.mass);
  o[1] = static_cast<T>(3.0 * m.qxx * s.second);
  o[2] = static_cast<T>(3.0 * m.qxy * s.second);
  o[3] = static_cast<T>(3.0 * m.qyy * s.second);
  o[4] = static_cast<T>(1.5 * (m.qxx + m.qyy) * s.second);
  o[5] = static_cast<T>(7.5 * m.oxxx * s.third);
  o[6] = static_cast<T>(7.5 * m.oxxy * s.third);
  o[7] = static_cast<T>(7.5 * m.oxyy * s.third);
  o[8] = static_cast<T>(7.5 * m.oyyy * s.third);
  o[9] = static_cast<T>(1.5 * (m.oxxx + m.oxyy) * s.third);
  o[10] = static_cast<T>(1.5 * (m.oxxy + m.oyyy) * s.third);
  o[11] = static_cast<T>(17.5 * m.hxxxx * s.fourth);
  o[12] = static_cast<T>(17.5 * m.hxxxy * s.fourth);
  o[13] = static_cast<T>(17.5 * m.hxxyy * s.fourth);
  o[14] = static_cast<T>(17.5 * m.hxyyy * s.fourth);
  o[15] = static_cast<T>(17.5 * m.hyyyy * s.fourth);
  o[16] = static_cast<T>(7.5 * (m.hxxxx + m.hxxyy) * s.fourth);
  o[17] = static_cast<T>(7.5 * (m.hxxxy + m.hxyyy) * s.fourth);
  o[18] = static_cast<T>(7.5 * (m.hxxyy + m.hyyyy) * s.fourth);
  o[19] = static_cast<T>(1.875 * (m.hxxxx + 2.0 * m.hxxyy + m.hyyyy) * s.fourth);
}

}  // namespace

void BarnesHut::Workspace::kernel_moments(std::size_t i, const bh::Moments& moments) {
  if (!single) {
    write_moments(moments, MomentScales{}, node64.data() + i * bh::kMoments);
    return;
  }
  const double second = frame.scale * frame.scale * frame.mass_scale;
  write_moments(moments,
                MomentScales{frame.mass_scale, second, second * frame.scale,
                             second * frame.scale * frame.scale},
                node32.data() + i * bh::kMoments);
}

void BarnesHut::Workspace::float_masses(std::uint32_t begin, std::uint32_t end) {
  for (std::uint32_t r = begin; r < end; ++r)
    sm32[r] = static_cast<float>(sm[r] * frame.mass_scale);
}

}  // namespace calder::nbody
