#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The GPU's figures for a review, in one command, on a machine with a GPU:
#
#   bench/gpu_review.sh [BUILD]     (BUILD: a build folder with bench_gpu; default build)
#
# Prints what Vulkan sees (`calder devices`), then bench_gpu's rows for the
# targets beside the CPU's of the same run: direct float32 sums at
# N = 2^20 (pairs/s; target >= 1.0e12), rain float32 at N = 10^7 in batches
# of 128 steps (body-steps/s; target >= 4.5e11), each with and without the
# transfers, float64 too; the CPU's direct sums at N = 2^17 and rain at 10^6.
# A few minutes. CALDER_GPU_DEVICE=N picks a device other than the first.
set -euo pipefail
build=${1:-build}
# NVIDIA's Vulkan driver where the loader doesn't find it by itself (the
# device machines keep it there).
nvidia_icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [[ -z "${VK_DRIVER_FILES:-}${VK_ICD_FILENAMES:-}" && -f $nvidia_icd ]]; then
  export VK_DRIVER_FILES=$nvidia_icd
fi
if [[ ! -x "$build/bench/bench_gpu" ]]; then
  echo "gpu_review: no $build/bench/bench_gpu (configure with -DCALDER_BUILD_BENCHMARKS=ON and" \
    "Vulkan found, then: cmake --build $build --target bench_gpu)" >&2
  exit 2
fi
if [[ -x "$build/apps/calder" ]]; then
  "$build/apps/calder" devices
fi
exec "$build/bench/bench_gpu" \
  "--benchmark_filter=Direct/N:(1048576|131072)/|Rain/N:(10000000|1000000)/" \
  --benchmark_counters_tabular=true
