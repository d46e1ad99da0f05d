// SPDX-License-Identifier: MIT
// calder: forces in 2D, after chapter 2 of The Nature of Code.
// One include for everything public.
#pragma once

#include "calder/detmath.hpp"
#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/fixed_step.hpp"
#include "calder/forces.hpp"
#include "calder/random.hpp"
#include "calder/scene.hpp"
#include "calder/trajectory.hpp"
#include "calder/vec2.hpp"
#include "calder/version.hpp"
#include "calder/world.hpp"
