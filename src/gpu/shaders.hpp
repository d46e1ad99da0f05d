// SPDX-License-Identifier: MIT
// calder::gpu internals: the kernels' SPIR-V, compiled from src/gpu/shaders
// at build time (CMakeLists.txt) and embedded here.
#pragma once

#include <cstdint>
#include <span>

#include "calder/forces.hpp"

namespace calder::gpu::spirv {

std::span<const std::uint32_t> direct32();  // shaders/direct.comp
std::span<const std::uint32_t> direct64();  // shaders/direct.comp, FLOAT64
std::span<const std::uint32_t> steps32();   // shaders/steps.comp
std::span<const std::uint32_t> steps64();   // shaders/steps.comp, FLOAT64

}  // namespace calder::gpu::spirv

namespace calder::gpu {

// The shaders' number of an inverse-square law (shaders/interface.h's kLaw*;
// steps.cpp).
std::int32_t shader_law(DistanceClamp law);

}  // namespace calder::gpu
