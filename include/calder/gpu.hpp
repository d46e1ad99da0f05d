// SPDX-License-Identifier: MIT
// calder::gpu: n-body sums and whole-world batches of steps on a GPU, through
// Vulkan compute (any Vulkan 1.1 device: NVIDIA, AMD, Intel, MoltenVK on
// macOS, or Mesa's lavapipe on the CPU, where the tests run).
//
//   calder::gpu::Context gpu;                 // the first device with compute
//   calder::gpu::direct_accelerations(gpu, x, y, mass, ax, ay, options);
//
//   calder::gpu::DeviceWorld rain(gpu, world);  // the world's bodies on the device
//   rain.step(1000);                            // no transfer but the fields' parameters
//   rain.read(world);                           // back to the host, when wanted
//
// Sums run in source order with no atomics: the same device gives the same
// bits run after run; float64 needs shaderFloat64. Steps run calder::bulk's
// fast arithmetics (Arithmetic::float32, float64) of the same fields; the
// book arithmetic (p5.js's bits) is the CPU's: a device's divide and square
// root are not correctly rounded (docs/DESIGN.md, "The GPU").
//
// Errors: a device that is asked for and missing, a world the kernels can't
// run, bad arrays: calder::InvalidArgument with one line; a Vulkan call that
// fails: calder::RunError naming it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "calder/backends.hpp"
#include "calder/nbody.hpp"
#include "calder/world.hpp"

namespace calder::gpu {

// A device as Vulkan reports it.
struct DeviceInfo {
  int index = 0;            // in devices()' order (Vulkan's enumeration)
  std::string name;         // "NVIDIA H100 80GB HBM3", "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string type;         // "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other"
  std::string api_version;  // "1.3.230"
  std::string driver;       // the driver's name and version where it reports them
  std::uint32_t vendor_id = 0;
  std::uint32_t device_id = 0;
  bool compute = false;                // has a queue family with compute
  bool float64 = false;                // shaderFloat64: the float64 kernels run
  std::uint64_t memory_bytes = 0;      // its largest device-local heap
  std::uint64_t max_buffer_bytes = 0;  // maxStorageBufferRange: the largest buffer a kernel reads
};

// Every device Vulkan sees, in its order; empty when it sees none (no Vulkan
// loader or driver, or no device): then *why_none, if given, says why.
std::vector<DeviceInfo> devices(std::string* why_none = nullptr);

// The environment variable that picks the device of Context(-1): an index
// of devices().
inline constexpr const char* kDeviceVariable = "CALDER_GPU_DEVICE";

// What crossed between host and device since the context was made (or
// reset_stats()), for the benchmarks.
struct TransferStats {
  std::uint64_t uploads = 0;  // copies to the device
  std::uint64_t upload_bytes = 0;
  std::uint64_t downloads = 0;  // copies back
  std::uint64_t download_bytes = 0;
  std::uint64_t dispatches = 0;  // kernel launches
  std::uint64_t submits = 0;     // command buffers submitted and waited for
};

// One Vulkan instance and logical device with one compute queue (RAII).
// Everything made with a context must be destroyed before it. One thread
// at a time.
class Context {
 public:
  // device: an index of devices(); -1: the one kDeviceVariable names, else
  // the first with compute. Throws calder::InvalidArgument (one line) when
  // there is no such device.
  explicit Context(int device = -1);
  ~Context();
  Context(Context&&) noexcept;
  Context& operator=(Context&&) noexcept;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  [[nodiscard]] const DeviceInfo& info() const;
  [[nodiscard]] const TransferStats& stats() const;
  void reset_stats();

  struct Impl;  // src/gpu/context.hpp
  [[nodiscard]] Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// --- n-body sums ----------------------------------------------------------------

// The direct O(n^2) sums of calder::nbody on the device: (ax, ay) +=
// accelerations, for options.law, options.G, softening or clamp bounds and
// options.precision (threads is ignored). float64 needs a device with
// shaderFloat64. Errors against calder::nbody::reference_accelerations:
// float64, within 1e-12 relative (measured ~1e-15 RMS); float32, those of
// calder::nbody's float32 path (Precision::float32). Same checks and errors
// as nbody::direct_accelerations.
void direct_accelerations(Context& context, std::span<const double> x, std::span<const double> y,
                          std::span<const double> mass, std::span<double> ax, std::span<double> ay,
                          const nbody::Options& options = {});

// The same with the bodies kept on the device between calls: upload once,
// evaluate as often as wanted, download when the sums are read.
class DirectSums {
 public:
  explicit DirectSums(Context& context);
  ~DirectSums();
  DirectSums(DirectSums&&) noexcept;
  DirectSums& operator=(DirectSums&&) noexcept;
  DirectSums(const DirectSums&) = delete;
  DirectSums& operator=(const DirectSums&) = delete;

  // Checks and uploads the bodies, for these options.
  void upload(std::span<const double> x, std::span<const double> y, std::span<const double> mass,
              const nbody::Options& options);
  // Runs the sums on the device (the results stay there).
  void evaluate();
  // Downloads the last evaluate()'s accelerations and adds them to (ax, ay).
  void add_to(std::span<double> ax, std::span<double> ay);
  [[nodiscard]] std::size_t size() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// --- whole-world steps -----------------------------------------------------------

// Why the GPU kernels can't step this world ("" when they can): they run
// the fields calder::bulk runs, semi-implicit Euler, the simultaneous order,
// and the arithmetics float32 and float64 (float64 on devices with
// shaderFloat64).
std::string unsupported(const World& world, const Context& context);

// A world's bodies on the device. Made from a World (its bodies, fields,
// boundary, dt, time and arithmetic at each step() call: the fields may be
// changed between calls); steps on the device and copies the bodies back
// only when asked. The World itself is not changed until read(world); it
// must outlive the DeviceWorld.
class DeviceWorld {
 public:
  // Uploads the world's bodies. Throws calder::InvalidArgument with
  // unsupported()'s reason.
  DeviceWorld(Context& context, const World& world);
  ~DeviceWorld();
  DeviceWorld(DeviceWorld&&) noexcept;
  DeviceWorld& operator=(DeviceWorld&&) noexcept;
  DeviceWorld(const DeviceWorld&) = delete;
  DeviceWorld& operator=(const DeviceWorld&) = delete;

  // count steps of the world's fields, batches of World::kBatchSteps, in
  // one submission. Copies the ops' parameters (and a noise wind's forces)
  // there and one word back: the first body whose position or velocity
  // became non-finite, for which it throws calder::RunError (the bodies are
  // then as the failing steps left them).
  void step(int count);
  // Copies positions and velocities back into `world` (the one it was made
  // from, or one with as many bodies). Its time and the accelerations
  // applied by hand before the DeviceWorld was made (which acted on its
  // first step) are left as they are: see time().
  void read(World& world) const;
  // Copies positions and velocities back into arrays of size() each.
  void read(std::span<double> x, std::span<double> y, std::span<double> vx,
            std::span<double> vy) const;
  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] double time() const;  // the world's time plus the steps taken
  [[nodiscard]] std::int64_t steps() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// --- the World's backends -------------------------------------------------------

// A StepBatchBackend (calder/backends.hpp) that runs World::step's batches on
// the process's device (install()): each call uploads the batch's bodies,
// runs its steps and downloads them (DeviceWorld keeps them there instead).
// It declines what the GPU can't run, as calder::bulk does: World::step then
// throws for the float32 and float64 arithmetics, and runs the book
// arithmetic (p5.js's bits, the CPU's by definition) in its plain loops.
// unsupported() says beforehand; the calder command refuses such a scene.
bool step_batch(const StepBatch& batch, std::string* why_not);
// A MutualAttractionBackend: NBodyMethod::direct on the device;
// barnes_hut is refused (calder::InvalidArgument: no Barnes-Hut on the GPU).
void mutual_attraction(const MutualAttraction& field, const FieldContext& context,
                       std::span<double> ax, std::span<double> ay);
// Opens the process's device (Context(device)), the one the two functions
// above use, if it isn't open yet (or another index is asked for); doesn't
// change the process defaults. Throws like Context(device).
Context& open(int device = -1);
// open(device), and makes the two functions above the process defaults, for
// every world that names no backend of its own (the `calder` command's
// --device gpu).
void install(int device = -1);
// The process's device, after open() or install(); nullptr before.
Context* installed();

}  // namespace calder::gpu
