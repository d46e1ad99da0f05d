// SPDX-License-Identifier: MIT
// Barnes-Hut, the moments (barnes_hut_moments.cpp), shared by the fast build
// and the reference build: a node's mass, centre of mass and second to fourth
// moments, from its bodies (the build kernels' leaf sums) or its children's
// (parallel axis theorem); its opening radius; the moments as the multipole
// kernels read them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "barnes_hut_tree.hpp"
#include "build_kernels.hpp"

namespace calder::nbody::bh {

// Mass, second, third and fourth moments about the centre of mass (qxx =
// sum m sx^2, ..., oxxy = sum m sx^2 sy, ..., hxxxy = sum m sx^3 sy, ...).
// No default values: Moments{} is all zeros, and a tree's moments are not
// zeroed as it grows (UnsetVector): the build writes each node's.
struct Moments {
  double mass;
  double qxx;
  double qxy;
  double qyy;
  double oxxx;
  double oxxy;
  double oxyy;
  double oyyy;
  double hxxxx;
  double hxxxy;
  double hxxyy;
  double hxyyy;
  double hyyyy;
};

// The cells of the root square, for the opening radii.
struct CellGeometry {
  double x0 = 0.0;
  double y0 = 0.0;
  double inv_theta = 0.0;                     // 1 / theta, +inf for theta = 0
  std::array<double, kBits + 1> cell_size{};  // side / 2^level, level 0 to kBits

  CellGeometry() = default;
  CellGeometry(const Square& square, double inv_theta_);
};

// A leaf's moments and centre of mass from its sums (BuildKernels::leaf_moments).
void leaf_moments(const double* sums, Node& node, Moments& mo);

// An inner node's centre of mass and moments (mo, zeroed) from its
// children's, which must be finished.
void merge_moments(const Node* nodes, const Moments* moments, Node& node, Moments& mo);

// Barnes' modified criterion: node's open2 for its cell, the cell at `level`
// of the root square holding Morton code `key`.
void set_opening_radius(Node& node, std::uint64_t key, int level, const CellGeometry& cells);

// Node i's moments as the kernels read them: tree.node64, or (tree.single)
// tree.node32 in the tree's frame.
void kernel_moments(BuiltTree& tree, std::size_t i, const Moments& moments);

// The float32 masses of bodies [begin, end) (tree.single).
void float_masses(BuiltTree& tree, std::uint32_t begin, std::uint32_t end);

}  // namespace calder::nbody::bh
