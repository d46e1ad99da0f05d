// SPDX-License-Identifier: MIT
// calder::movers from an installed calder: with the kernels installed, a
// thousand movers under gravity g = (0, 0.1) fall as semi-implicit Euler says:
// after n steps from rest, y = y0 + 0.1 * n (n + 1) / 2.
#include <calder/calder.hpp>
#include <calder/movers.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  calder::movers::install();
  calder::World world;
  world.add(calder::Gravity{});
  std::vector<calder::BodyId> ids;
  for (int i = 0; i < 1000; ++i) {
    ids.push_back(world.add_body(calder::BodyDef{.position = {double(i), 0}, .mass = 1.0}));
  }
  if (!calder::movers::unsupported(world).empty()) {
    std::fprintf(stderr, "consumer_movers: %s\n", calder::movers::unsupported(world).c_str());
    return 1;
  }
  world.step(10);
  const double expected = 0.1 * 10 * 11 / 2;
  for (const auto id : ids) {
    if (std::abs(world.position(id).y - expected) > 1e-9) {
      std::fprintf(stderr, "consumer_movers: expected y = %g, got %.17g\n", expected,
                   world.position(id).y);
      return 1;
    }
  }
  std::printf("consumer_movers: ok (kernels %s)\n", calder::movers::kernel_name());
  return 0;
}
