// SPDX-License-Identifier: MIT
// calder::bulk from an installed calder: linking it is enough (no call
// registers the kernels). A thousand movers under gravity g = (0, 0.1) fall
// as semi-implicit Euler says: after n steps from rest, y = y0 + 0.1 * n (n + 1) / 2,
// in book arithmetic and in float32, which only the kernels run.
#include <calder/bulk.hpp>
#include <calder/calder.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

bool falls_as_euler_says(calder::Arithmetic arithmetic, double tolerance) {
  calder::World world({.arithmetic = arithmetic});
  world.add(calder::Gravity{});
  std::vector<calder::BodyId> ids;
  for (int i = 0; i < 1000; ++i) {
    ids.push_back(world.add_body(calder::BodyDef{.position = {double(i), 0}, .mass = 1.0}));
  }
  if (!calder::bulk::unsupported(world).empty()) {
    std::fprintf(stderr, "consumer_bulk: %s\n", calder::bulk::unsupported(world).c_str());
    return false;
  }
  world.step(10);
  const double expected = 0.1 * 10 * 11 / 2;
  for (const auto id : ids) {
    if (std::abs(world.position(id).y - expected) > tolerance) {
      std::fprintf(stderr, "consumer_bulk: %s: expected y = %g, got %.17g\n",
                   std::string(calder::arithmetic_name(arithmetic)).c_str(), expected,
                   world.position(id).y);
      return false;
    }
  }
  return true;
}

}  // namespace

int main() {
  try {
    if (!falls_as_euler_says(calder::Arithmetic::book, 1e-9)) return 1;
    if (!falls_as_euler_says(calder::Arithmetic::float32, 1e-5)) return 1;
  } catch (const calder::Error& e) {
    std::fprintf(stderr, "consumer_bulk: %s\n", e.what());
    return 1;
  }
  std::printf("consumer_bulk: ok (kernels %s)\n", calder::bulk::kernel_name());
  return 0;
}
