// SPDX-License-Identifier: MIT
// calder::nbody from an installed calder: two bodies 5 apart, G = 1, no
// softening. Newton: body 0 (at the origin) accelerates toward body 1 (mass 2,
// at (3, 4)) by 2 / 25 along (3, 4) / 5 = (0.048, 0.064).
#include <calder/nbody.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  const std::vector<double> x{0, 3}, y{0, 4}, mass{1, 2};
  std::vector<double> ax(2, 0.0), ay(2, 0.0);
  calder::nbody::direct_accelerations(x, y, mass, ax, ay);
  if (std::abs(ax[0] - 0.048) > 1e-12 || std::abs(ay[0] - 0.064) > 1e-12) {
    std::fprintf(stderr, "consumer_nbody: expected (0.048, 0.064), got (%.17g, %.17g)\n", ax[0],
                 ay[0]);
    return 1;
  }
  std::printf("consumer_nbody: ok (kernels %s)\n", calder::nbody::kernel_name());
  return 0;
}
