// SPDX-License-Identifier: MIT
// calder::gpu's interface between the host (src/gpu/*.cpp) and the shaders
// (src/gpu/shaders/*.comp): every number both sides must agree on, written
// once. C++ includes it as a header; GLSL through glslang's #include
// (GL_GOOGLE_include_directive). CALDER_GPU_INT names a signed constant,
// CALDER_GPU_UINT an unsigned one.
#ifndef CALDER_GPU_SHADERS_INTERFACE_H
#define CALDER_GPU_SHADERS_INTERFACE_H

#ifdef __cplusplus
#include <cstdint>
#define CALDER_GPU_INT(name, value) inline constexpr std::int32_t name = value;
#define CALDER_GPU_UINT(name, value) inline constexpr std::uint32_t name = value;
namespace calder::gpu::shader {
#else
#define CALDER_GPU_INT(name, value) const int name = value;
#define CALDER_GPU_UINT(name, value) const uint name = uint(value);
#endif

// The inverse-square laws, numbered as calder::DistanceClamp (and so
// calder::nbody::Law): steps.comp's attractor, direct.comp's kLaw.
CALDER_GPU_INT(kLawClampDistance, 0)         // w = 1 / (r d^2), d = clamp(r, lo, hi)
CALDER_GPU_INT(kLawClampSquaredDistance, 1)  // w = 1 / (r q), q = clamp(r^2, lo, hi)
CALDER_GPU_INT(kLawPlummer, 2)               // w = 1 / (r^2 + eps^2)^(3/2)

// steps.comp's op kinds (an op's op_ints.x).
CALDER_GPU_INT(kOpUniform, 0)
CALDER_GPU_INT(kOpGravityScaled, 1)  // g for every body: folded into the constant acceleration
CALDER_GPU_INT(kOpDrag, 2)
CALDER_GPU_INT(kOpFriction, 3)
CALDER_GPU_INT(kOpAttractor, 4)
CALDER_GPU_INT(kOpEdgeForce, 5)
CALDER_GPU_INT(kOpFan, 6)
CALDER_GPU_INT(kOpLift, 7)

// An op's flags (op_ints.y).
CALDER_GPU_INT(kOpEverywhere, 1)    // drag: no region
CALDER_GPU_INT(kOpNeverReverse, 2)  // drag, friction: at most the velocity in a step
CALDER_GPU_INT(kOpPerStep, 4)       // uniform: each step's force from per_step

// Friction's surface (op_ints.z; an attractor's holds its law).
CALDER_GPU_INT(kEdgeLeft, 0)
CALDER_GPU_INT(kEdgeRight, 1)
CALDER_GPU_INT(kEdgeTop, 2)
CALDER_GPU_INT(kEdgeBottom, 3)

// The boundary's flags (the push constants' boundary).
CALDER_GPU_UINT(kBounce, 1)
CALDER_GPU_UINT(kWrap, 2)
CALDER_GPU_UINT(kUseRadius, 4)
CALDER_GPU_UINT(kBefore, 8)  // before the update
CALDER_GPU_UINT(kLeft, 16)
CALDER_GPU_UINT(kRight, 32)
CALDER_GPU_UINT(kTop, 64)
CALDER_GPU_UINT(kBottom, 128)

// The slots of an op's reals in op_reals, kSlots an op.
CALDER_GPU_INT(kSlotFx, 0)
CALDER_GPU_INT(kSlotFy, 1)
CALDER_GPU_INT(kSlotC, 2)  // drag: c; friction: mu; edge_force, fan: strength; lift: coefficient
CALDER_GPU_INT(kSlotNormal, 3)
CALDER_GPU_INT(kSlotXMin, 4)
CALDER_GPU_INT(kSlotXMax, 5)
CALDER_GPU_INT(kSlotYMin, 6)
CALDER_GPU_INT(kSlotYMax, 7)
CALDER_GPU_INT(kSlotTolerance, 8)
CALDER_GPU_INT(kSlotPx, 9)
CALDER_GPU_INT(kSlotPy, 10)
CALDER_GPU_INT(kSlotGm, 11)
CALDER_GPU_INT(kSlotLo, 12)
CALDER_GPU_INT(kSlotHi, 13)
CALDER_GPU_INT(kSlotEps, 14)
CALDER_GPU_INT(kSlotReach, 15)  // fan: reach; edge_force: margin
CALDER_GPU_INT(kSlots, 16)

// steps.comp's fixed ops: a plan of at most this many has its kinds, flags
// and laws or edges as specialization constants.
CALDER_GPU_INT(kFixedOpsMax, 4)

#ifdef __cplusplus
}  // namespace calder::gpu::shader
#endif
#undef CALDER_GPU_INT
#undef CALDER_GPU_UINT

#endif  // CALDER_GPU_SHADERS_INTERFACE_H
