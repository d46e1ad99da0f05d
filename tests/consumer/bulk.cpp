// SPDX-License-Identifier: MIT
// calder::bulk from an installed calder: with the kernels installed, a
// thousand movers under gravity g = (0, 0.1) fall as semi-implicit Euler says:
// after n steps from rest, y = y0 + 0.1 * n (n + 1) / 2.
#include <calder/bulk.hpp>
#include <calder/calder.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  calder::bulk::install();
  calder::World world;
  world.add(calder::Gravity{});
  std::vector<calder::BodyId> ids;
  for (int i = 0; i < 1000; ++i) {
    ids.push_back(world.add_body(calder::BodyDef{.position = {double(i), 0}, .mass = 1.0}));
  }
  if (!calder::bulk::unsupported(world).empty()) {
    std::fprintf(stderr, "consumer_bulk: %s\n", calder::bulk::unsupported(world).c_str());
    return 1;
  }
  world.step(10);
  const double expected = 0.1 * 10 * 11 / 2;
  for (const auto id : ids) {
    if (std::abs(world.position(id).y - expected) > 1e-9) {
      std::fprintf(stderr, "consumer_bulk: expected y = %g, got %.17g\n", expected,
                   world.position(id).y);
      return 1;
    }
  }
  std::printf("consumer_bulk: ok (kernels %s)\n", calder::bulk::kernel_name());
  return 0;
}
