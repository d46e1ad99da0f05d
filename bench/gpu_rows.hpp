// SPDX-License-Identifier: MIT
// calder-bench's rows for calder::gpu: the direct sums and the rain on the
// first Vulkan device, with and without the transfers, to print beside the
// CPU's rows of the same run. (bench_command.cpp calls gpu_rows() where the
// build has calder::gpu; bench_gpu.cpp's GpuRows smoke-runs it.)
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "calder/world.hpp"

namespace calder::bench {

struct GpuRow {
  std::string name;  // "gpu direct float32, N = 1048576, bodies on the device"
  double value = 0;  // per second
  std::string unit;  // "pairs/s" or "body-steps/s"
  std::string note;  // the bytes copied per evaluation or batch
};

// Measures the rows (quick: small sizes, one repetition; else N = 2^20 for
// the sums, 10^7 drops for the rain, as the GPU issue's targets). Returns
// one row saying why when there is no device (name "gpu", value 0).
std::vector<GpuRow> gpu_rows(bool quick);

// The rain scene with n drops (the canvas grown with n: the same density as
// the built-in scene's 1000 drops on 640 x 240), stepped by `backend`.
World gpu_rain_world(std::size_t n, Arithmetic arithmetic, StepBatchBackend backend);

// The device the rows ran on ("NVIDIA H100 80GB HBM3 (discrete GPU, Vulkan
// 1.3.277)"), or why there is none.
std::string gpu_device_text();

}  // namespace calder::bench
