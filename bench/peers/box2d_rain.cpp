// SPDX-License-Identifier: MIT
// Box2D 2.4 running calder's rain scene: see box2d_rain.hpp.
//
// Units. Box2D is tuned for objects of 0.1 to 10 m moving at most
// b2_maxTranslation = 2 m per step, in float; calder's rain is in pixels and
// frames (640 x 240 px canvas, speeds of a few px/frame). We map
//   1 px    = s = 0.01 m      (canvas 6.4 m x 2.4 m; radii 0.01 to 0.06 m)
//   1 frame = h = 1/60 s      (Step(1/60): one Box2D step per calder frame)
// and keep mass as is (1 calder mass unit = 1 kg). Then
//   position  x_m = s x_px                       (0.01)
//   velocity  v_m = (s / h) v_px                 (0.6 m/s per px/frame)
//   accel.    a_m = (s / h^2) a_px               (36 m/s^2 per px/frame^2)
//   force     F_m = m a_m = (s / h^2) F_px       (36 N per calder force unit)
//   gravity   g_m = (s / h^2) g_px               (0.1 -> 3.6 m/s^2)
//   drag      F = -c |v| v: c_m |v_m| v_m = (s^2 / h^2) c_m |v_px| v_px must equal
//             (s / h^2) c_px |v_px| v_px, so c_m = c_px / s   (0.01 -> 1 kg/m)
// and Box2D's island integrator (v += h F / m; x += h v) is calder's
// semi-implicit Euler with dt = 1 frame, step for step: the same motion,
// rounded to float. The speed limit is 2 m/step = 200 px/frame, far above the
// rain's terminal speeds (sqrt(g m / c) ~ 5.5 px/frame for m = 3).
//
// y keeps calder's orientation (down): the world's gravity is zero and gravity
// is a force applied per body like drag, so Box2D has no notion of "up" here.
#include "peers/box2d_rain.hpp"

#include <box2d/box2d.h>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace calder::peers {
namespace {

constexpr double kMetresPerPixel = 0.01;         // s
constexpr double kSecondsPerFrame = 1.0 / 60.0;  // h
constexpr double kVelocityScale = kMetresPerPixel / kSecondsPerFrame;
constexpr double kAccelerationScale = kMetresPerPixel / (kSecondsPerFrame * kSecondsPerFrame);

// No contact ever exists (collisions filtered, or no fixtures), so the
// velocity and position iterations only loop over zero constraints: Box2D's
// recommended 8 and 3 cost the same as 1 and 1.
constexpr int kVelocityIterations = 8;
constexpr int kPositionIterations = 3;

float to_float(double v) { return static_cast<float>(v); }

}  // namespace

struct Box2dRain::Impl {
  // Per body, in metres and newtons, precomputed so step() does only the rule.
  struct Body {
    b2Body* body;
    float weight;  // m g_m: gravity scaled by mass
    float left;    // r: the smallest x the centre may have
    float right;   // W - r
    float bottom;  // H - r (y down)
  };

  b2World world{b2Vec2(0.0f, 0.0f)};  // gravity is applied per body, as a force
  std::vector<Body> bodies;
  float drag = 0.0f;         // c_m, kg/m
  float restitution = 0.0f;  // e
};

Box2dRain::Box2dRain(std::span<const double> x, std::span<const double> y,
                     std::span<const double> vx, std::span<const double> vy,
                     std::span<const double> mass, std::span<const double> radius,
                     const RainParams& params, Box2dBodies kind)
    : impl_(std::make_unique<Impl>()) {
  const std::size_t n = x.size();
  if (y.size() != n || vx.size() != n || vy.size() != n || mass.size() != n || radius.size() != n) {
    throw std::invalid_argument("Box2dRain: x, y, vx, vy, mass and radius differ in size");
  }
  // Sleeping bodies would do no work, which would flatter Box2D in a benchmark.
  impl_->world.SetAllowSleeping(false);
  impl_->drag = to_float(params.drag / kMetresPerPixel);
  impl_->restitution = to_float(params.restitution);
  const double g = params.gravity * kAccelerationScale;
  impl_->bodies.reserve(n);

  for (std::size_t i = 0; i < n; ++i) {
    if (!(mass[i] > 0.0) || !std::isfinite(mass[i])) {
      throw std::invalid_argument("Box2dRain: masses must be positive and finite");
    }
    if (!(radius[i] >= 0.0) || !std::isfinite(radius[i])) {
      throw std::invalid_argument("Box2dRain: radii must be non-negative and finite");
    }
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position.Set(to_float(x[i] * kMetresPerPixel), to_float(y[i] * kMetresPerPixel));
    def.linearVelocity.Set(to_float(vx[i] * kVelocityScale), to_float(vy[i] * kVelocityScale));
    def.linearDamping = 0.0f;
    def.angularDamping = 0.0f;
    def.fixedRotation = true;
    def.allowSleep = false;
    b2Body* body = impl_->world.CreateBody(&def);

    if (kind == Box2dBodies::circles) {
      b2CircleShape shape;
      shape.m_radius = to_float(radius[i] * kMetresPerPixel);
      b2FixtureDef fixture;
      fixture.shape = &shape;
      fixture.density = 1.0f;  // overridden by SetMassData below
      // One negative group: Box2D's default contact filter never lets two of
      // its members collide, yet their proxies stay in the broad phase (pairs
      // are found, then rejected), which is the cost we want to measure.
      fixture.filter.groupIndex = -1;
      body->CreateFixture(&fixture);
    }
    // Last, since CreateFixture recomputes the mass from the density.
    b2MassData mass_data;
    mass_data.mass = to_float(mass[i]);
    mass_data.center.SetZero();
    mass_data.I = 0.0f;  // fixed rotation
    body->SetMassData(&mass_data);

    const double r = radius[i];
    impl_->bodies.push_back({body, to_float(mass[i] * g), to_float(r * kMetresPerPixel),
                             to_float((params.width - r) * kMetresPerPixel),
                             to_float((params.height - r) * kMetresPerPixel)});
  }
}

Box2dRain::~Box2dRain() = default;
Box2dRain::Box2dRain(Box2dRain&&) noexcept = default;
Box2dRain& Box2dRain::operator=(Box2dRain&&) noexcept = default;

void Box2dRain::step() {
  Impl& impl = *impl_;
  const float c = impl.drag;
  const float e = impl.restitution;

  // 1. Forces, from the velocity at the start of the frame (as calder does).
  for (const Impl::Body& b : impl.bodies) {
    const b2Vec2 v = b.body->GetLinearVelocity();
    const float speed = v.Length();
    b.body->ApplyForceToCenter(b2Vec2(-c * speed * v.x, b.weight - c * speed * v.y), false);
  }

  // 2. Semi-implicit Euler (and an empty contact solve); forces are cleared after.
  impl.world.Step(static_cast<float>(kSecondsPerFrame), kVelocityIterations, kPositionIterations);

  // 3. The bounce on the radius: left/right exclusive, then bottom; no top wall.
  for (const Impl::Body& b : impl.bodies) {
    b2Vec2 p = b.body->GetPosition();
    b2Vec2 v = b.body->GetLinearVelocity();
    bool bounced = false;
    if (p.x > b.right) {
      p.x = b.right;
      v.x *= -e;
      bounced = true;
    } else if (p.x < b.left) {
      p.x = b.left;
      v.x *= -e;
      bounced = true;
    }
    if (p.y > b.bottom) {
      p.y = b.bottom;
      v.y *= -e;
      bounced = true;
    }
    if (bounced) {
      b.body->SetTransform(p, 0.0f);
      b.body->SetLinearVelocity(v);
    }
  }
}

std::size_t Box2dRain::size() const { return impl_->bodies.size(); }

double Box2dRain::x(std::size_t i) const {
  return static_cast<double>(impl_->bodies[i].body->GetPosition().x) / kMetresPerPixel;
}

double Box2dRain::y(std::size_t i) const {
  return static_cast<double>(impl_->bodies[i].body->GetPosition().y) / kMetresPerPixel;
}

double Box2dRain::vx(std::size_t i) const {
  return static_cast<double>(impl_->bodies[i].body->GetLinearVelocity().x) / kVelocityScale;
}

double Box2dRain::vy(std::size_t i) const {
  return static_cast<double>(impl_->bodies[i].body->GetLinearVelocity().y) / kVelocityScale;
}

}  // namespace calder::peers
