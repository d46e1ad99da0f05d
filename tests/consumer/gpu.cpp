// SPDX-License-Identifier: MIT
// calder::gpu from an installed calder: on the first Vulkan device (lavapipe
// in CI), two bodies of mass 1 at distance 2 pull each other with
// G m / r^2 = 0.25, Plummer's law without softening.
#include <calder/gpu.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  calder::gpu::Context gpu;
  const std::vector<double> x{-1.0, 1.0}, y{0.0, 0.0}, m{1.0, 1.0};
  std::vector<double> ax(2, 0.0), ay(2, 0.0);
  calder::nbody::Options options;
  options.precision = calder::nbody::Precision::float32;
  calder::gpu::direct_accelerations(gpu, x, y, m, ax, ay, options);
  if (std::abs(ax[0] - 0.25) > 1e-6 || std::abs(ax[1] + 0.25) > 1e-6 || ay[0] != 0.0) {
    std::fprintf(stderr, "consumer_gpu: expected ax = (0.25, -0.25), got (%.9g, %.9g)\n", ax[0],
                 ax[1]);
    return 1;
  }
  std::printf("consumer_gpu: ok (%s)\n", gpu.info().name.c_str());
  return 0;
}
