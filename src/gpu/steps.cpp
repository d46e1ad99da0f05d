// SPDX-License-Identifier: MIT
// calder::gpu: whole-world batches of steps on the device (shaders/steps.comp):
// DeviceWorld, which keeps the bodies there, and the StepBatchBackend, which
// copies them there and back for each of World::step's batches.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <variant>
#include <vector>

#include "../bulk/plan.hpp"
#include "../step_batch.hpp"
#include "calder/error.hpp"
#include "calder/gpu.hpp"
#include "context.hpp"
#include "shaders.hpp"
#include "shaders/interface.h"
#include "steps.hpp"

namespace calder::gpu {

namespace {

constexpr std::uint32_t kGroup = 256;
constexpr std::uint32_t kNoBody = std::numeric_limits<std::uint32_t>::max();

// The numbers steps.comp shares with this file: op kinds, flags, edges,
// laws, boundary flags and the slots of an op's reals.
using namespace shader;

template <class Real>
struct StepsPush {
  std::uint32_t n, groups, steps, ops, boundary, first, total, pad;
  Real dt, width, height, reverse, cx, cy;
};

std::int32_t edge_index(Edge e) {
  switch (e) {
    case Edge::left:
      return kEdgeLeft;
    case Edge::right:
      return kEdgeRight;
    case Edge::top:
      return kEdgeTop;
    case Edge::bottom:
      return kEdgeBottom;
  }
  return kEdgeBottom;
}

}  // namespace

std::int32_t shader_law(DistanceClamp law) {
  switch (law) {
    case DistanceClamp::distance:
      return kLawClampDistance;
    case DistanceClamp::squared_distance:
      return kLawClampSquaredDistance;
    case DistanceClamp::none:
      return kLawPlummer;
  }
  return kLawPlummer;
}

namespace {

std::uint32_t boundary_flags(const Boundary& b) {
  std::uint32_t f = 0;
  if (b.kind == BoundaryKind::bounce) f |= kBounce;
  if (b.kind == BoundaryKind::wrap) f |= kWrap;
  if (b.use_radius) f |= kUseRadius;
  if (b.timing == BoundaryTiming::before_update) f |= kBefore;
  if (b.edges.left) f |= kLeft;
  if (b.edges.right) f |= kRight;
  if (b.edges.top) f |= kTop;
  if (b.edges.bottom) f |= kBottom;
  return f;
}

// steps.comp's op kinds (interface.h).
enum class ShaderOp : std::int32_t {
  uniform = kOpUniform,
  gravity_scaled = kOpGravityScaled,  // g for every body: folded into the constant acceleration
  drag = kOpDrag,
  friction = kOpFriction,
  attractor = kOpAttractor,
  edge_force = kOpEdgeForce,
  fan = kOpFan,
  lift = kOpLift,
};

// One op as steps.comp reads it: its kind, flags, law or edge (which), the
// forces of each step when it has them, and its reals.
template <class R>
struct OpRecord {
  ShaderOp kind = ShaderOp::uniform;
  std::int32_t flags = 0;
  std::int32_t which = 0;
  const double* per_step = nullptr;
  std::array<R, std::size_t{kSlots}> reals{};
};

// --- each field kind's law as an op record (the fast arithmetic's law) ---

template <class R>
void encode(const FieldLaw<Gravity>::Law<R>& law, OpRecord<R>& op) {
  op.kind = law.scaled ? ShaderOp::gravity_scaled : ShaderOp::uniform;
  op.reals[kSlotFx] = law.gx;
  op.reals[kSlotFy] = law.gy;
}

template <class R>
void encode(const FieldLaw<Wind>::Law<R>& law, OpRecord<R>& op) {
  op.reals[kSlotFx] = law.fx;
  op.reals[kSlotFy] = law.fy;
}

template <class R>
void encode(const FieldLaw<Helium>::Law<R>& law, OpRecord<R>& op) {
  op.reals[kSlotFx] = law.fx;
  op.reals[kSlotFy] = law.fy;
}

template <class R>
void encode(const FieldLaw<NoiseWind>::Law<R>& law, OpRecord<R>& op) {
  op.reals[kSlotFx] = law.fx;
  op.reals[kSlotFy] = law.fy;
  op.per_step = law.per_step;
}

template <class R>
void encode(const FieldLaw<Drag>::Law<R>& law, OpRecord<R>& op) {
  constexpr R kInf = std::numeric_limits<R>::infinity();
  op.kind = ShaderOp::drag;
  op.flags = kOpEverywhere | (law.never_reverse ? kOpNeverReverse : 0);
  op.reals[kSlotC] = law.c;
  op.reals[kSlotXMin] = -kInf;
  op.reals[kSlotXMax] = kInf;
  op.reals[kSlotYMin] = -kInf;
  op.reals[kSlotYMax] = kInf;
}

template <class R>
void encode(const FieldLaw<Liquid>::Law<R>& law, OpRecord<R>& op) {
  op.kind = ShaderOp::drag;
  op.flags = law.never_reverse ? kOpNeverReverse : 0;
  op.reals[kSlotC] = law.c;
  op.reals[kSlotXMin] = law.x_min;
  op.reals[kSlotXMax] = law.x_max;
  op.reals[kSlotYMin] = law.y_min;
  op.reals[kSlotYMax] = law.y_max;
}

template <class R>
void encode(const FieldLaw<Friction>::Law<R>& law, OpRecord<R>& op) {
  op.kind = ShaderOp::friction;
  op.flags = law.never_reverse ? kOpNeverReverse : 0;
  op.which = edge_index(law.surface);
  op.reals[kSlotC] = law.mu;
  op.reals[kSlotNormal] = law.normal;
  op.reals[kSlotTolerance] = law.tolerance;
}

// The fast form: G M w r, w = 1 / (d_c^2 d), 1 / (q d) or 1 / s^3 (G M in
// double, then rounded, as the CPU's kernels take it).
template <class R>
void encode(const FieldLaw<Attractor>::Law<R>& law, OpRecord<R>& op) {
  op.kind = ShaderOp::attractor;
  op.which = shader_law(law.clamp);
  op.reals[kSlotPx] = law.px;
  op.reals[kSlotPy] = law.py;
  op.reals[kSlotGm] = law.gm;
  op.reals[kSlotLo] = law.lo;
  op.reals[kSlotHi] = law.hi;
  op.reals[kSlotEps] = law.eps;
}

template <class R>
void encode(const FieldLaw<EdgeForce>::Law<R>& law, OpRecord<R>& op) {
  op.kind = ShaderOp::edge_force;
  op.reals[kSlotC] = law.strength;
  op.reals[kSlotReach] = law.margin;
}

template <class R>
void encode(const FieldLaw<Fan>::Law<R>& law, OpRecord<R>& op) {
  op.kind = ShaderOp::fan;
  op.reals[kSlotPx] = law.px;
  op.reals[kSlotPy] = law.py;
  op.reals[kSlotC] = law.strength;
  op.reals[kSlotReach] = law.reach;
}

template <class R>
void encode(const FieldLaw<Lift>::Law<R>& law, OpRecord<R>& op) {
  op.kind = ShaderOp::lift;
  op.reals[kSlotC] = law.coefficient;
}

// Every kind with a law has an encode: a new kind can't be skipped silently.
template <class F>
concept Encoded = requires(const typename FieldLaw<F>::template Law<float>& f32,
                           const typename FieldLaw<F>::template Law<double>& f64,
                           OpRecord<float>& op32, OpRecord<double>& op64) {
  encode(f32, op32);
  encode(f64, op64);
};
template <class... Kinds>
constexpr bool every_law_encoded(const std::variant<Kinds...>*) {
  return ((!HasLaw<Kinds> || Encoded<Kinds>)&&...);
}
static_assert(every_law_encoded(static_cast<const Field*>(nullptr)),
              "a field kind has a law but no encode (its op for steps.comp)");

// The op record of a plan's op in precision R.
template <class R>
OpRecord<R> record_of(const bulk::detail::Op& op) {
  OpRecord<R> record;
  std::visit(
      [&record](const auto& kind_law) {
        // A kind without a law has an empty KindLaw, which compile() never makes.
        if constexpr (requires { kind_law.law; }) encode<R>(kind_law.law, record);
      },
      op.law<R>());
  return record;
}

}  // namespace

// --- Stepper ---

Stepper::Stepper(Context::Impl& context) : context_(&context) {}

void Stepper::upload(const BodyColumnsOf<std::span<const double>>& bodies, bool float64) {
  float64_ = float64;
  n_ = bodies.x.size();
  if (float64) {
    upload_as<double>(bodies);
  } else {
    upload_as<float>(bodies);
  }
}

template <class R>
void Stepper::upload_as(const BodyColumnsOf<std::span<const double>>& b) {
  std::vector<R> state(4 * n_), accel(2 * n_), props(4 * n_);
  for (std::size_t i = 0; i < n_; ++i) {
    state[4 * i] = R(b.x[i]);
    state[4 * i + 1] = R(b.y[i]);
    state[4 * i + 2] = R(b.vx[i]);
    state[4 * i + 3] = R(b.vy[i]);
    accel[2 * i] = R(b.ax[i]);
    accel[2 * i + 1] = R(b.ay[i]);
    props[4 * i] = R(1.0 / b.mass[i]);
    props[4 * i + 1] = R(b.radius[i]);
    props[4 * i + 2] = std::isnan(b.friction[i]) ? R(-1) : R(b.friction[i]);  // -1: the field's
    props[4 * i + 3] = R(b.drag_area[i]);
  }
  state_ = buffer_of<R>(*context_, state.size());
  accel_ = buffer_of<R>(*context_, accel.size());
  props_ = buffer_of<R>(*context_, props.size());
  if (bad_.handle() == VK_NULL_HANDLE) bad_ = buffer_of<std::uint32_t>(*context_, 1);
  const Context::Impl::Upload copies[] = {{&state_, state.data(), state.size() * sizeof(R)},
                                          {&accel_, accel.data(), accel.size() * sizeof(R)},
                                          {&props_, props.data(), props.size() * sizeof(R)}};
  context_->upload(copies);
  ++generation_;
}

template <class R>
void Stepper::upload_ops(const bulk::detail::Plan& plan, int steps, Real2<R>& constant) {
  std::vector<std::int32_t> ints;
  std::vector<R> reals, per_step;
  constant = {R(0), R(0)};
  for (const bulk::detail::Op& op : plan.ops) {
    const OpRecord<R> record = record_of<R>(op);
    if (record.kind == ShaderOp::gravity_scaled) {  // g for every body: folded
      constant.x += record.reals[kSlotFx];
      constant.y += record.reals[kSlotFy];
      continue;
    }
    std::int32_t flags = record.flags;
    std::int32_t offset = 0;
    if (record.per_step != nullptr) {
      flags |= kOpPerStep;
      offset = static_cast<std::int32_t>(per_step.size());
      for (int s = 0; s < 2 * steps; ++s) per_step.push_back(R(record.per_step[s]));
    }
    ints.insert(ints.end(), {static_cast<std::int32_t>(record.kind), flags, record.which, offset});
    reals.insert(reals.end(), record.reals.begin(), record.reals.end());
  }
  ops_ = static_cast<std::uint32_t>(ints.size() / 4);
  // The specialization: workgroup, fixed op count (or -1), kinds, flags,
  // laws or edges.
  constexpr std::size_t kFixed = kFixedOpsMax;
  constants_.assign(2 + 3 * kFixed, 0);
  constants_[0] = static_cast<std::int32_t>(kGroup);
  constants_[1] = ops_ <= kFixed ? static_cast<std::int32_t>(ops_) : -1;
  for (std::size_t k = 0; k < ops_ && ops_ <= kFixed; ++k) {
    constants_[2 + k] = ints[4 * k];
    constants_[2 + kFixed + k] = ints[4 * k + 1];
    constants_[2 + 2 * kFixed + k] = ints[4 * k + 2];
  }
  const auto grow = [&](Buffer& b, std::size_t bytes) {
    if (b.bytes() < std::max<std::size_t>(bytes, 4)) {
      b = Buffer(*context_, std::max<std::size_t>(bytes, 64));
      ++generation_;
    }
  };
  grow(op_ints_, ints.size() * sizeof(std::int32_t));
  grow(op_reals_, reals.size() * sizeof(R));
  grow(per_step_, per_step.size() * sizeof(R));
  const std::uint32_t none = kNoBody;
  const Context::Impl::Upload copies[] = {
      {&op_ints_, ints.data(), ints.size() * sizeof(std::int32_t)},
      {&op_reals_, reals.data(), reals.size() * sizeof(R)},
      {&per_step_, per_step.data(), per_step.size() * sizeof(R)},
      {&bad_, &none, sizeof none}};
  context_->upload(copies);
}

template <class R>
std::size_t Stepper::run_as(const bulk::detail::Plan& plan, int steps) {
  Real2<R> constant{};
  upload_ops<R>(plan, steps, constant);
  std::vector<std::int32_t> key = constants_;
  key.push_back(float64_ ? 64 : 32);
  Cached& cached = kernels_[key];
  if (!cached.kernel.valid()) {
    cached.kernel = Kernel(*context_, float64_ ? spirv::steps64() : spirv::steps32(), 7,
                           sizeof(StepsPush<R>), constants_);
  }
  Kernel& kernel = cached.kernel;
  if (cached.generation != generation_) {
    const Buffer* const buffers[] = {&state_,    &accel_,    &props_, &op_ints_,
                                     &op_reals_, &per_step_, &bad_};
    kernel.bind(buffers);
    cached.generation = generation_;
  }
  const auto groups = static_cast<std::uint32_t>((n_ + kGroup - 1) / kGroup);
  StepsPush<R> push{static_cast<std::uint32_t>(n_),
                    groups,
                    0,
                    ops_,
                    boundary_flags(plan.boundary),
                    0,
                    static_cast<std::uint32_t>(steps),
                    0,
                    R(plan.dt),
                    R(plan.width),
                    R(plan.height),
                    R(-plan.boundary.restitution),
                    constant.x,
                    constant.y};
  context_->submit([&](VkCommandBuffer cb) {
    for (int first = 0; first < steps; first += World::kBatchSteps) {
      push.first = static_cast<std::uint32_t>(first);
      push.steps = static_cast<std::uint32_t>(std::min(World::kBatchSteps, steps - first));
      kernel.record(cb, &push, groups);
    }
  });
  std::uint32_t bad = kNoBody;
  const Context::Impl::Download copy[] = {{&bad_, &bad, sizeof bad}};
  context_->download(copy);
  return bad == kNoBody ? n_ : static_cast<std::size_t>(bad);
}

std::size_t Stepper::run(const bulk::detail::Plan& plan, int steps) {
  if (n_ == 0 || steps <= 0) return n_;
  return float64_ ? run_as<double>(plan, steps) : run_as<float>(plan, steps);
}

template <class R>
void Stepper::download_as(std::span<double> x, std::span<double> y, std::span<double> vx,
                          std::span<double> vy) const {
  std::vector<R> state(4 * n_);
  const Context::Impl::Download copy[] = {{&state_, state.data(), state.size() * sizeof(R)}};
  context_->download(copy);
  for (std::size_t i = 0; i < n_; ++i) {
    x[i] = static_cast<double>(state[4 * i]);
    y[i] = static_cast<double>(state[4 * i + 1]);
    vx[i] = static_cast<double>(state[4 * i + 2]);
    vy[i] = static_cast<double>(state[4 * i + 3]);
  }
}

void Stepper::download(std::span<double> x, std::span<double> y, std::span<double> vx,
                       std::span<double> vy) const {
  if (n_ == 0) return;
  if (float64_) {
    download_as<double>(x, y, vx, vy);
  } else {
    download_as<float>(x, y, vx, vy);
  }
}

// --- what the kernels run ---

std::string unsupported_settings(Arithmetic arithmetic, const Boundary& boundary,
                                 const std::deque<Field>& fields, const Context::Impl& context) {
  if (arithmetic == Arithmetic::book) {
    return "the GPU runs arithmetic float32 and float64 (book, p5.js's bits, needs the CPU)";
  }
  if (arithmetic == Arithmetic::float64 && !context.info.float64) {
    return "arithmetic float64 needs a device with shaderFloat64 (" + context.info.name +
           " has none)";
  }
  if (boundary.inset != 0.0 || !boundary.periodic) {
    return "the GPU kernels have no boundary with an inset or a non-periodic wrap";
  }
  for (const Field& field : fields) {
    const auto* wind = std::get_if<NoiseWind>(&field);
    if (wind != nullptr && wind->accumulate)
      return "the GPU kernels have no accumulating noise_wind";
  }
  return bulk::detail::unsupported_field(fields);
}

std::string unsupported(const World& world, const Context& context) {
  if (world.integrator() != Integrator::semi_implicit_euler) {
    return "the GPU kernels integrate with semi_implicit_euler only";
  }
  if (world.update_order() != UpdateOrder::simultaneous) {
    return "the GPU kernels need the simultaneous update order";
  }
  if (world.max_speed() > 0.0) return "the GPU kernels have no speed limit (max_speed)";
  return unsupported_settings(world.arithmetic(), world.boundary(), world.fields(), context.impl());
}

// --- DeviceWorld ---

struct DeviceWorld::State {
  Context::Impl* context;
  const World* world;
  Stepper stepper;
  bulk::detail::Plan plan;
  double time = 0.0;
  std::int64_t steps = 0;
  explicit State(Context::Impl& c, const World& w) : context(&c), world(&w), stepper(c) {}
};

DeviceWorld::DeviceWorld(Context& context, const World& world)
    : state_(std::make_unique<State>(context.impl(), world)) {
  if (const std::string why = unsupported(world, context); !why.empty()) {
    throw InvalidArgument("gpu::DeviceWorld: " + why);
  }
  const BodyView view = world.bodies();
  state_->stepper.upload(view, world.arithmetic() == Arithmetic::float64);
  state_->time = world.time();
}

DeviceWorld::~DeviceWorld() = default;
DeviceWorld::DeviceWorld(DeviceWorld&&) noexcept = default;
DeviceWorld& DeviceWorld::operator=(DeviceWorld&&) noexcept = default;

void DeviceWorld::step(int count) {
  if (count < 0) {
    throw InvalidArgument("gpu::DeviceWorld::step: count must be >= 0 (got " +
                          std::to_string(count) + ")");
  }
  if (count == 0) return;
  State& s = *state_;
  const World& w = *s.world;
  if (const std::string why =
          unsupported_settings(w.arithmetic(), w.boundary(), w.fields(), *s.context);
      !why.empty()) {
    throw InvalidArgument("gpu::DeviceWorld::step: " + why);
  }
  for (const Field& field : w.fields()) validate(field);
  StepBatch batch;
  batch.fields = &w.fields();
  batch.boundary = w.boundary();
  batch.width = w.width();
  batch.height = w.height();
  batch.dt = w.dt();
  batch.time = s.time;
  batch.steps = count;
  batch.arithmetic = w.arithmetic();
  batch.noise = &w.noise();
  std::string why;
  if (!bulk::detail::compile(batch, s.plan, &why))
    throw InvalidArgument("gpu::DeviceWorld: " + why);
  const std::size_t bad = s.stepper.run(s.plan, count);
  for (int k = 0; k < count; ++k) s.time += w.dt();
  s.steps += count;
  if (bad < s.stepper.size()) {
    throw RunError("gpu::DeviceWorld::step: body " + std::to_string(bad) +
                   " left the finite numbers (a position or velocity is NaN or infinite)");
  }
}

void DeviceWorld::read(std::span<double> x, std::span<double> y, std::span<double> vx,
                       std::span<double> vy) const {
  const std::size_t n = state_->stepper.size();
  if (x.size() != n || y.size() != n || vx.size() != n || vy.size() != n) {
    throw InvalidArgument("gpu::DeviceWorld::read: each array must have " + std::to_string(n) +
                          " elements");
  }
  state_->stepper.download(x, y, vx, vy);
}

void DeviceWorld::read(World& world) const {
  const std::size_t n = state_->stepper.size();
  if (world.body_count() != n) {
    throw InvalidArgument("gpu::DeviceWorld::read: the world has " +
                          std::to_string(world.body_count()) + " bodies, the device " +
                          std::to_string(n));
  }
  std::vector<double> x(n), y(n), vx(n), vy(n);
  state_->stepper.download(x, y, vx, vy);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyId id = world.body(i);
    world.set_position(id, {x[i], y[i]});
    world.set_velocity(id, {vx[i], vy[i]});
  }
}

std::size_t DeviceWorld::size() const { return state_->stepper.size(); }
double DeviceWorld::time() const { return state_->time; }
std::int64_t DeviceWorld::steps() const { return state_->steps; }

}  // namespace calder::gpu
