// SPDX-License-Identifier: MIT
#include "peers/rain_world.hpp"

#include <cmath>
#include <variant>

#include "calder/scene.hpp"

namespace calder::peers {

World rain_world(std::size_t drops, Arithmetic arithmetic, int threads) {
  Scene scene = builtin_scene("rain");
  const double scale = std::sqrt(static_cast<double>(drops) / 1000.0);
  scene.world.width *= scale;
  scene.world.height *= scale;
  scene.world.arithmetic = arithmetic;
  scene.world.threads = threads;
  BodyGroup& group = scene.bodies.front();
  group.count = drops;
  group.x = Draw::uniform(0.0, scene.world.width);
  group.y = Draw::uniform(0.0, scene.world.height);
  Simulation simulation(std::move(scene));
  return simulation.world();
}

Box2dRain box2d_rain(const World& world, Box2dBodies kind) {
  RainParams params;
  params.width = world.width();
  params.height = world.height();
  params.restitution = world.boundary().restitution;
  for (const Field& field : world.fields()) {
    if (const auto* g = std::get_if<Gravity>(&field)) params.gravity = g->g.y;
    if (const auto* d = std::get_if<Drag>(&field)) params.drag = d->c;
  }
  const BodyView b = world.bodies();
  return Box2dRain(b.x, b.y, b.vx, b.vy, b.mass, b.radius, params, kind);
}

}  // namespace calder::peers
