#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The GPU's figures for a review, in one command, on a machine with a GPU:
#
#   bench/gpu_review.sh [BUILD]         run them (BUILD: a build folder with
#                                       bench/bench_gpu; default build)
#   bench/gpu_review.sh --pack BUILD DIR  copy bench_gpu, the calder command and
#                                       the shared libraries they need that a
#                                       bare machine may lack into DIR, for a
#                                       machine without the build's packages:
#                                       there, run bench/gpu_review.sh DIR
#
# Prints what Vulkan sees (`calder devices`), then bench_gpu's rows for the
# targets beside the CPU's of the same run: direct float32 sums at
# N = 2^20 (pairs/s; target >= 1.0e12), rain float32 at N = 10^7 in batches
# of 128 steps (body-steps/s; target >= 4.5e11), each with and without the
# transfers, float64 too; the CPU's direct sums at N = 2^17 and rain at 10^6.
# A few minutes. CALDER_GPU_DEVICE=N picks a device other than the first. A
# build packed for another machine should be configured with
# -DCALDER_PORTABLE=ON (its CPU kernels are otherwise -march=native).
set -euo pipefail
if [[ "${1:-}" == "--pack" ]]; then
  build=$2 dir=$3
  mkdir -p "$dir/bench" "$dir/apps" "$dir/lib"
  cp "$build/bench/bench_gpu" "$dir/bench/"
  if [[ -x "$build/apps/calder" ]]; then cp "$build/apps/calder" "$dir/apps/"; fi
  for program in "$dir/bench/bench_gpu" "$dir/apps/calder"; do
    [[ -x $program ]] || continue
    ldd "$program" | awk '/=> \// {print $3}' | grep -E 'libbenchmark|libgomp|libtomlplusplus|libcairo|libgif|libSDL2|libpixman|libpng|libfontconfig|libfreetype' |
      while read -r lib; do cp -L "$lib" "$dir/lib/"; done
  done
  echo "gpu_review: packed into $dir (there: bench/gpu_review.sh $dir)"
  exit 0
fi
build=${1:-build}
if [[ -d "$build/lib" ]]; then export LD_LIBRARY_PATH="$build/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"; fi
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
  "$build/apps/calder" devices || true
fi
exec "$build/bench/bench_gpu" \
  "--benchmark_filter=Direct/N:(1048576|131072)/|Rain/N:(10000000|1000000)/" \
  --benchmark_counters_tabular=true
