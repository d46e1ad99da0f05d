// SPDX-License-Identifier: MIT
// Barnes-Hut, the reference build (barnes_hut_reference.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "barnes_hut_moments.hpp"
#include "barnes_hut_tree.hpp"

namespace calder::nbody::bh {

// The reference build's buffers, kept between calls.
struct ReferenceScratch {
  struct Keyed {
    std::uint64_t key;
    std::uint32_t index;
  };
  std::vector<Keyed> bodies;  // by Morton code, then (in a leaf) by index
  std::vector<Moments> moments;
};

// The plain serial build: the tree of BuiltTree's contract, built the
// simplest way. The solver's path for few bodies and the tests' oracle for
// the fast build (TreeBuilder): for the same bodies and settings both give
// the same tree, to the bit (node numbers aside).
void reference_build(std::span<const double> x, std::span<const double> y,
                     std::span<const double> mass, const BuildSettings& settings, BuiltTree& tree,
                     ReferenceScratch& scratch);

}  // namespace calder::nbody::bh
