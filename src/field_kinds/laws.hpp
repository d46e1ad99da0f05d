// SPDX-License-Identifier: MIT
// calder internals: the law of every field kind (FieldLaw, law.hpp), as
// calder/fields.hpp gathers their structs.
#pragma once

#include "attractor.hpp"
#include "calder/fields.hpp"
#include "custom_force.hpp"
#include "drag.hpp"
#include "edge_force.hpp"
#include "fan.hpp"
#include "friction.hpp"
#include "gravity.hpp"
#include "helium.hpp"
#include "law.hpp"
#include "lift.hpp"
#include "liquid.hpp"
#include "mutual_attraction.hpp"
#include "noise_wind.hpp"
#include "wind.hpp"
