// SPDX-License-Identifier: MIT
// calder::gpu: the embedded SPIR-V (see shaders.hpp).
#include "shaders.hpp"

#include <cstdint>

// glslangValidator --vn writes `const uint32_t name[] = {...};`.
namespace calder::gpu::spirv {
namespace {
using std::uint32_t;
#include "direct32.h"
#include "direct64.h"
#include "steps32.h"
#include "steps64.h"
}  // namespace

std::span<const std::uint32_t> direct32() { return kDirect32; }
std::span<const std::uint32_t> direct64() { return kDirect64; }
std::span<const std::uint32_t> steps32() { return kSteps32; }
std::span<const std::uint32_t> steps64() { return kSteps64; }

}  // namespace calder::gpu::spirv
