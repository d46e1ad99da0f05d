// SPDX-License-Identifier: MIT
// calder::gpu: direct n-body sums on the device (shaders/direct.comp).
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "../nbody/common.hpp"
#include "calder/error.hpp"
#include "calder/gpu.hpp"
#include "context.hpp"
#include "shaders.hpp"

namespace calder::gpu {

namespace {

// Bodies per workgroup and per tile of sources in shared memory.
constexpr std::uint32_t kGroup = 256;

template <class Real>
struct DirectPush {
  std::uint32_t n_pad;
  std::uint32_t groups;
  Real eps2, lo, hi;
};

// Specialization constants: workgroup size, law, whether coincident pairs
// must be masked (clamped laws, or Plummer without softening).
std::array<std::int32_t, 3> constants_of(nbody::Law law, bool softened) {
  const bool mask = law != nbody::Law::plummer || !softened;
  return {static_cast<std::int32_t>(kGroup), shader_law(law), mask ? 1 : 0};
}

}  // namespace

struct DirectSums::State {
  Context::Impl* context;
  Buffer positions, masses, sums;
  Kernel kernel;
  std::array<std::int32_t, 3> constants{};
  bool float64 = false;
  std::size_t n = 0;
  std::size_t n_pad = 0;
  double factor = 1.0;  // sum in the caller's units = factor * kernel sum
  nbody::detail::LawParams law{};
  bool evaluated = false;

  void make_kernel(bool want64, const std::array<std::int32_t, 3>& want) {
    if (kernel.valid() && want64 == float64 && want == constants) return;
    kernel = Kernel(*context, want64 ? spirv::direct64() : spirv::direct32(), 3,
                    want64 ? sizeof(DirectPush<double>) : sizeof(DirectPush<float>), want);
    float64 = want64;
    constants = want;
  }

  void upload32(std::span<const double> x, std::span<const double> y, std::span<const double> mass,
                const nbody::Options& options) {
    const nbody::detail::FloatFrame frame = nbody::detail::float_frame(x, y, mass, options.G);
    law = nbody::detail::law_params(options, frame);
    factor = frame.factor;
    // Two-float positions relative to the centre (padding: body 0, massless).
    std::vector<float> xy(4 * n_pad);
    std::vector<float> m(n_pad, 0.0f);
    for (std::size_t i = 0; i < n_pad; ++i) {
      const std::size_t from = i < n ? i : 0;
      const double px = (x[from] - frame.cx) * frame.scale;
      const double py = (y[from] - frame.cy) * frame.scale;
      xy[4 * i] = static_cast<float>(px);
      xy[4 * i + 1] = static_cast<float>(py);
      xy[4 * i + 2] = static_cast<float>(px - static_cast<double>(xy[4 * i]));
      xy[4 * i + 3] = static_cast<float>(py - static_cast<double>(xy[4 * i + 1]));
      if (i < n) m[i] = static_cast<float>(mass[i] * frame.mass_scale);
    }
    positions = buffer_of<float>(*context, 4 * n_pad);
    masses = buffer_of<float>(*context, n_pad);
    sums = buffer_of<float>(*context, 4 * n_pad);
    const Context::Impl::Upload copies[] = {{&positions, xy.data(), xy.size() * sizeof(float)},
                                            {&masses, m.data(), m.size() * sizeof(float)}};
    context->upload(copies);
  }

  void upload64(std::span<const double> x, std::span<const double> y, std::span<const double> mass,
                const nbody::Options& options) {
    law = nbody::detail::law_params(options, nbody::detail::FloatFrame{});
    factor = options.G;
    std::vector<double> xy(2 * n_pad);
    std::vector<double> m(n_pad, 0.0);
    for (std::size_t i = 0; i < n_pad; ++i) {
      const std::size_t from = i < n ? i : 0;
      xy[2 * i] = x[from];
      xy[2 * i + 1] = y[from];
      if (i < n) m[i] = mass[i];
    }
    positions = buffer_of<double>(*context, 2 * n_pad);
    masses = buffer_of<double>(*context, n_pad);
    sums = buffer_of<double>(*context, 2 * n_pad);
    const Context::Impl::Upload copies[] = {{&positions, xy.data(), xy.size() * sizeof(double)},
                                            {&masses, m.data(), m.size() * sizeof(double)}};
    context->upload(copies);
  }
};

DirectSums::DirectSums(Context& context) : state_(std::make_unique<State>()) {
  state_->context = &context.impl();
}
DirectSums::~DirectSums() = default;
DirectSums::DirectSums(DirectSums&&) noexcept = default;
DirectSums& DirectSums::operator=(DirectSums&&) noexcept = default;

std::size_t DirectSums::size() const { return state_->n; }

void DirectSums::upload(std::span<const double> x, std::span<const double> y,
                        std::span<const double> mass, const nbody::Options& options) {
  {  // (validate checks output arrays too: two of the right size)
    std::vector<double> out_x(x.size());
    std::vector<double> out_y(x.size());
    nbody::detail::validate("gpu::DirectSums::upload", x, y, mass, out_x, out_y, options);
  }
  State& s = *state_;
  const bool want64 = options.precision == nbody::Precision::float64;
  if (want64 && !s.context->info.float64) {
    throw InvalidArgument("gpu::DirectSums: float64 sums need a device with shaderFloat64 (" +
                          s.context->info.name + " has none)");
  }
  s.evaluated = false;
  s.n = x.size();
  s.n_pad = std::max<std::size_t>(kGroup, (s.n + kGroup - 1) / kGroup * kGroup);
  if (s.n == 0) return;
  if (want64) {
    s.upload64(x, y, mass, options);
  } else {
    s.upload32(x, y, mass, options);
  }
  const bool softened = want64 ? s.law.eps2 > 0.0 : s.law.eps2_f > 0.0f;
  s.make_kernel(want64, constants_of(options.law, softened));
  const Buffer* const bound[] = {&s.positions, &s.masses, &s.sums};
  s.kernel.bind(bound);
}

void DirectSums::evaluate() {
  State& s = *state_;
  if (s.n == 0) return;
  const auto groups = static_cast<std::uint32_t>(s.n_pad / kGroup);
  const auto n_pad = static_cast<std::uint32_t>(s.n_pad);
  if (s.float64) {
    const DirectPush<double> push{n_pad, groups, s.law.eps2, s.law.lo, s.law.hi};
    s.context->submit([&](VkCommandBuffer cb) { s.kernel.record(cb, &push, groups); });
  } else {
    const DirectPush<float> push{n_pad, groups, s.law.eps2_f, s.law.lo_f, s.law.hi_f};
    s.context->submit([&](VkCommandBuffer cb) { s.kernel.record(cb, &push, groups); });
  }
  s.evaluated = true;
}

void DirectSums::add_to(std::span<double> ax, std::span<double> ay) {
  State& s = *state_;
  if (ax.size() != s.n || ay.size() != s.n) {
    throw InvalidArgument("gpu::DirectSums::add_to: ax and ay must have " + std::to_string(s.n) +
                          " elements (got " + std::to_string(ax.size()) + " and " +
                          std::to_string(ay.size()) + ")");
  }
  if (s.n == 0) return;
  if (!s.evaluated) throw InvalidArgument("gpu::DirectSums::add_to: call evaluate() first");
  if (s.float64) {
    std::vector<double> sums(2 * s.n);
    const Context::Impl::Download copy[] = {{&s.sums, sums.data(), sums.size() * sizeof(double)}};
    s.context->download(copy);
    for (std::size_t i = 0; i < s.n; ++i) {
      ax[i] += s.factor * sums[2 * i];
      ay[i] += s.factor * sums[2 * i + 1];
    }
  } else {
    std::vector<float> sums(4 * s.n);
    const Context::Impl::Download copy[] = {{&s.sums, sums.data(), sums.size() * sizeof(float)}};
    s.context->download(copy);
    for (std::size_t i = 0; i < s.n; ++i) {
      const double sx = static_cast<double>(sums[4 * i]) + static_cast<double>(sums[4 * i + 2]);
      const double sy = static_cast<double>(sums[4 * i + 1]) + static_cast<double>(sums[4 * i + 3]);
      ax[i] += s.factor * sx;
      ay[i] += s.factor * sy;
    }
  }
}

void direct_accelerations(Context& context, std::span<const double> x, std::span<const double> y,
                          std::span<const double> mass, std::span<double> ax, std::span<double> ay,
                          const nbody::Options& options) {
  nbody::detail::validate("gpu::direct_accelerations", x, y, mass, ax, ay, options);
  DirectSums sums(context);
  sums.upload(x, y, mass, options);
  sums.evaluate();
  sums.add_to(ax, ay);
}

}  // namespace calder::gpu
