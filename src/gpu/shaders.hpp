// SPDX-License-Identifier: MIT
// calder::gpu internals: the kernels' SPIR-V, compiled from src/gpu/shaders
// at build time (CMakeLists.txt) and embedded here.
#pragma once

#include <cstdint>
#include <span>

namespace calder::gpu::spirv {

std::span<const std::uint32_t> direct32();  // shaders/direct.comp
std::span<const std::uint32_t> direct64();  // shaders/direct.comp, FLOAT64
std::span<const std::uint32_t> steps32();   // shaders/steps.comp
std::span<const std::uint32_t> steps64();   // shaders/steps.comp, FLOAT64

}  // namespace calder::gpu::spirv
