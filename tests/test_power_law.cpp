// SPDX-License-Identifier: MIT
// The power law with a repulsive core (exercise 2.13's "other force laws"),
// against closed forms.
#include <gtest/gtest.h>

#include <calder/calder.hpp>
#include <cmath>

namespace {

using calder::AttractionLaw;
using calder::DistanceClamp;
using calder::Vec2;

AttractionLaw unclamped(double exponent, double repulsion = 0.0, double repulsion_exponent = 3.0) {
  AttractionLaw law = AttractionLaw::newtonian(1.5);
  law.exponent = exponent;
  law.repulsion = repulsion;
  law.repulsion_exponent = repulsion_exponent;
  return law;
}

// Signed magnitude toward the source at distance d along +x.
double toward(const AttractionLaw& law, double d, double source_mass = 2.0, double mass = 3.0) {
  return calder::attraction({d, 0.0}, source_mass, {0.0, 0.0}, mass, law).x;
}

TEST(PowerLaw, ExponentTwoIsTheBookLawBitForBit) {
  AttractionLaw book = AttractionLaw::book();
  AttractionLaw explicit_two = AttractionLaw::book();
  explicit_two.exponent = 2.0;
  for (const double d : {1.0, 7.3, 12.0, 40.0}) {
    const Vec2 a = calder::attraction({d, 0.3 * d}, 20.0, {0.0, 0.0}, 2.0, book);
    const Vec2 b = calder::attraction({d, 0.3 * d}, 20.0, {0.0, 0.0}, 2.0, explicit_two);
    EXPECT_EQ(a, b) << d;
  }
}

TEST(PowerLaw, ExponentOneIsWeakerWhenClose) {
  // |F| = G M m / d: halving the distance only doubles the force (vs four times).
  const AttractionLaw law = unclamped(1.0);
  EXPECT_DOUBLE_EQ(toward(law, 10.0), 1.5 * 2.0 * 3.0 / 10.0);
  EXPECT_DOUBLE_EQ(toward(law, 5.0) / toward(law, 10.0), 2.0);
  // exponent -1: a spring-like pull growing with distance, G M m d.
  EXPECT_DOUBLE_EQ(toward(unclamped(-1.0), 4.0), 1.5 * 2.0 * 3.0 * 4.0);
}

TEST(PowerLaw, RepulsiveCoreAttractsFarAndRepelsNear) {
  // |F| = G M m / d^2 - R M m / d^3 changes sign at d0 = R / G.
  const AttractionLaw law = unclamped(2.0, 30.0, 3.0);
  const double d0 = 30.0 / 1.5;
  EXPECT_GT(toward(law, 2.0 * d0), 0.0);  // attracts far
  EXPECT_LT(toward(law, 0.5 * d0), 0.0);  // repels near
  EXPECT_NEAR(toward(law, d0), 0.0, 1e-15);
  const double d = 7.0;
  EXPECT_DOUBLE_EQ(toward(law, d), 1.5 * 2.0 * 3.0 / (d * d) - 30.0 * 2.0 * 3.0 / (d * d * d));
}

TEST(PowerLaw, PotentialDerivativeIsTheForceInEveryRegime) {
  // dU/dd = |F| (attraction positive), by central differences, for the
  // unclamped law and for the distance clamp below, inside and above it.
  AttractionLaw clamped = unclamped(1.5, 4.0, 2.5);
  clamped.clamp = DistanceClamp::distance;
  clamped.min = 2.0;
  clamped.max = 30.0;
  for (const AttractionLaw& law : {unclamped(1.0), unclamped(1.5, 4.0, 2.5), clamped}) {
    for (const double d : {0.5, 1.7, 3.0, 11.0, 45.0}) {
      const double h = 1e-5 * d;
      const double slope = (calder::attraction_potential(d + h, 2.0, 3.0, law) -
                            calder::attraction_potential(d - h, 2.0, 3.0, law)) /
                           (2.0 * h);
      EXPECT_NEAR(slope, toward(law, d), 1e-6 * (1.0 + std::abs(slope))) << "d " << d;
    }
  }
}

TEST(PowerLaw, EnergyIsConservedUnderTheRepulsiveCore) {
  // Two bodies bound by attract-far/repel-near oscillate; Verlet keeps the
  // total energy (kinetic + the law's potential) to second order in dt.
  const auto run = [](double dt) {
    calder::World world({.dt = dt, .integrator = calder::Integrator::velocity_verlet});
    world.add_body({.position = {0, 0}, .velocity = {0, 0.05}, .mass = 1});
    world.add_body({.position = {30, 0}, .velocity = {0, -0.05}, .mass = 1});
    world.add(calder::MutualAttraction{.law = unclamped(2.0, 20.0, 3.0)});
    const double e0 = calder::total_energy(world);
    double worst = 0.0;
    for (int k = 0; k < static_cast<int>(2000 / dt); ++k) {
      world.step();
      worst = std::max(worst, std::abs(calder::total_energy(world) - e0) / std::abs(e0));
    }
    return worst;
  };
  const double coarse = run(0.5);
  const double fine = run(0.25);
  EXPECT_LT(fine, 1e-3);
  EXPECT_NEAR(coarse / fine, 4.0, 1.0);  // second order
}

TEST(PowerLaw, InvalidCombinationsAreRejected) {
  AttractionLaw law = AttractionLaw::newtonian(1.0, 0.5);
  law.exponent = 1.0;
  EXPECT_THROW(law.validate("test"), calder::Error);  // softening needs exponent 2
  law = AttractionLaw::newtonian();
  law.repulsion = -1.0;
  EXPECT_THROW(law.validate("test"), calder::Error);
  law = AttractionLaw::newtonian();
  law.exponent = std::nan("");
  EXPECT_THROW(law.validate("test"), calder::Error);
}

}  // namespace
