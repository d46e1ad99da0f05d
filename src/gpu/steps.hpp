// SPDX-License-Identifier: MIT
// calder::gpu internals: a world's bodies on the device and the kernel that
// steps them (steps.cpp, shaders/steps.comp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "../bulk/plan.hpp"
#include "calder/body_columns.hpp"
#include "context.hpp"

namespace calder::gpu {

template <class R>
struct Real2 {
  R x, y;
};

// The bodies' state (x, y, vx, vy), accelerations applied by hand, and
// properties (1 / mass, radius, own friction, drag area) in device buffers,
// in float or double.
class Stepper {
 public:
  explicit Stepper(Context::Impl& context);
  void upload(const BodyColumnsOf<std::span<const double>>& bodies, bool float64);
  // Runs `steps` steps of the plan (its per-step forces for that many
  // steps), batches of World::kBatchSteps in one submission; returns the
  // first body left non-finite, or size().
  std::size_t run(const bulk::detail::Plan& plan, int steps);
  void download(std::span<double> x, std::span<double> y, std::span<double> vx,
                std::span<double> vy) const;
  [[nodiscard]] std::size_t size() const { return n_; }

 private:
  template <class R>
  void upload_as(const BodyColumnsOf<std::span<const double>>& bodies);
  template <class R>
  void upload_ops(const bulk::detail::Plan& plan, int steps, Real2<R>& constant);
  template <class R>
  std::size_t run_as(const bulk::detail::Plan& plan, int steps);
  template <class R>
  void download_as(std::span<double> x, std::span<double> y, std::span<double> vx,
                   std::span<double> vy) const;

  Context::Impl* context_;
  Buffer state_, accel_, props_, op_ints_, op_reals_, per_step_, bad_;
  // Pipelines by precision and specialization (steps.comp's constants:
  // the workgroup, and the kinds of up to 4 ops); each bound to the buffers
  // of one generation (a buffer made again starts the next).
  struct Cached {
    Kernel kernel;
    std::uint64_t generation = 0;
  };
  std::map<std::vector<std::int32_t>, Cached> kernels_;
  std::vector<std::int32_t> constants_;  // the last upload_ops' plan's
  std::uint64_t generation_ = 1;
  std::size_t n_ = 0;
  std::uint32_t ops_ = 0;
  bool float64_ = false;
};

// Why the kernels can't run these settings ("" when they can).
std::string unsupported_settings(Arithmetic arithmetic, const Boundary& boundary,
                                 const std::deque<Field>& fields, const Context::Impl& context);

}  // namespace calder::gpu
