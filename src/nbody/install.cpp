// SPDX-License-Identifier: MIT
// calder::nbody and the World: the kernels' options for a core attraction
// law (options_for), and the fast methods of MutualAttraction
// (NBodyMethod::direct, NBodyMethod::barnes_hut) registered as the process
// default of calder/backends.hpp while the program starts, so that linking
// calder::nbody is all a world needs. CMake's calder::nbody and
// calder-nbody.pc link with --undefined=calder_nbody_linked, which keeps this
// object (and so its initialiser) in a program that names nothing else of
// calder::nbody.
#include <span>

#include "calder/backends.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/nbody.hpp"

namespace calder::nbody {

Options options_for(const AttractionLaw& law) {
  if (law.custom) {
    throw Error("nbody::options_for: a custom force law has no n-body kernel");
  }
  if (!law.inverse_square()) {
    throw Error(
        "nbody::options_for: the n-body kernels support the inverse-square law only (got "
        "exponent " +
        calder::detail::format_number(law.exponent) + ", repulsion " +
        calder::detail::format_number(law.repulsion) + ")");
  }
  law.validate("nbody::options_for");
  Options o;
  o.G = law.G;
  o.law = law.clamp;  // the same enum (nbody::Law)
  o.softening = law.softening;
  o.min_distance = law.min;
  o.max_distance = law.max;
  return o;
}

// The core has added the central body's pulls; this adds the pairs'.
void mutual_attraction(const MutualAttraction& field, const FieldContext& context,
                       std::span<double> ax, std::span<double> ay) {
  const BodyView& b = context.bodies;
  Options options = options_for(field.law);  // throws for a custom law
  options.precision = field.single_precision ? Precision::float32 : Precision::float64;
  options.threads = field.threads;
  if (field.method == NBodyMethod::barnes_hut) {
    BarnesHutOptions bh;
    static_cast<Options&>(bh) = options;
    bh.theta = field.theta;
    // One solver per calling thread keeps its buffers from step to step.
    thread_local BarnesHut solver;
    solver.accelerations(b.x, b.y, b.mass, ax, ay, bh);
  } else {
    direct_accelerations(b.x, b.y, b.mass, ax, ay, options);
  }
}

namespace {

const bool registered = [] {
  set_mutual_attraction_backend(mutual_attraction);
  return true;
}();

}  // namespace

}  // namespace calder::nbody

// The symbol the link option names (its value is not used).
extern "C" {
extern const char calder_nbody_linked;
const char calder_nbody_linked = 1;
}
