// SPDX-License-Identifier: MIT
// Barnes-Hut, the reference build: BuiltTree's contract built the plainest
// way, serially. Morton codes in the root square, one sort by code, then the
// tree depth first: a node is the smallest cell holding its bodies, split into
// its non-empty quadrants while it holds more than leaf_size bodies of more
// than one code; a leaf's bodies are put back in index order. Moments come
// from the same helpers as the fast build's (barnes_hut_moments.hpp), so for
// the same bodies both give the same tree to the bit; node numbers may
// differ. The solver builds small trees this way; the tests check the fast
// build against it.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "barnes_hut_reference.hpp"
#include "build_kernels.hpp"

namespace calder::nbody::bh {

namespace {

using Keyed = ReferenceScratch::Keyed;

class ReferenceBuild {
 public:
  ReferenceBuild(const BuildSettings& settings, BuiltTree& tree, std::vector<Keyed>& bodies)
      : settings_(settings), tree_(tree), bodies_(bodies) {}

  // Node `index` over bodies [begin, end) and its subtree, at `depth`.
  void node(std::uint32_t index, std::uint32_t begin, std::uint32_t end, int depth, bool in_group) {
    tree_.depth = std::max(tree_.depth, depth);
    const std::size_t count = end - begin;
    const int level = shared_levels(bodies_[begin].key ^ bodies_[end - 1].key);
    const bool leaf = count <= settings_.leaf_size || level == kBits;
    if (!in_group && (count <= settings_.group_size || leaf)) {
      tree_.groups.push_back(index);
      in_group = true;
    }
    Node& n = tree_.nodes[index];
    n.begin = begin;
    n.end = end;
    n.child = 0;
    n.children = 0;
    if (leaf) {
      ++tree_.leaves;
      std::sort(bodies_.data() + begin, bodies_.data() + end,
                [](const Keyed& a, const Keyed& b) { return a.index < b.index; });
      return;
    }
    // The quadrants: the two bits below the shared prefix, in order.
    const int shift = 2 * (kBits - 1 - level);
    std::uint32_t bounds[5] = {begin, begin, begin, begin, end};
    for (std::uint32_t q = 1; q < 4; ++q) {
      bounds[q] = bounds[q - 1];
      while (bounds[q] < end && ((bodies_[bounds[q]].key >> shift) & 3u) < q) ++bounds[q];
    }
    const auto first = static_cast<std::uint32_t>(tree_.nodes.size());
    std::uint32_t children = 0;
    for (int q = 0; q < 4; ++q) children += bounds[q + 1] > bounds[q] ? 1 : 0;
    tree_.nodes.resize(first + children);
    tree_.parent.resize(first + children);
    tree_.nodes[index].child = first;
    tree_.nodes[index].children = children;
    std::uint32_t c = first;
    for (int q = 0; q < 4; ++q) {
      if (bounds[q + 1] == bounds[q]) continue;
      tree_.parent[c] = index;
      node(c++, bounds[q], bounds[q + 1], depth + 1, in_group);
    }
  }

 private:
  const BuildSettings& settings_;
  BuiltTree& tree_;
  std::vector<Keyed>& bodies_;
};

}  // namespace

void reference_build(std::span<const double> x, std::span<const double> y,
                     std::span<const double> mass, const BuildSettings& settings, BuiltTree& tree,
                     ReferenceScratch& scratch) {
  const std::size_t n = x.size();
  // The root square: the bounding box's lower corner and larger side.
  const auto [xmin, xmax] = std::minmax_element(x.begin(), x.end());
  const auto [ymin, ymax] = std::minmax_element(y.begin(), y.end());
  double side = std::max(*xmax - *xmin, *ymax - *ymin);
  if (!(side > 0.0)) side = 1.0;  // one point
  tree.square = Square{*xmin, *ymin, side};
  const MortonCoder code(tree.square.x0, tree.square.y0, side);
  std::vector<Keyed>& bodies = scratch.bodies;
  bodies.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    bodies[i] = Keyed{code(x[i], y[i]), static_cast<std::uint32_t>(i)};
  std::sort(bodies.begin(), bodies.end(), [](const Keyed& a, const Keyed& b) {
    return a.key != b.key ? a.key < b.key : a.index < b.index;
  });

  tree.nodes.assign(1, Node{});
  tree.parent.assign(1, ~std::uint32_t{0});
  tree.groups.clear();
  tree.depth = 0;
  tree.leaves = 0;
  ReferenceBuild(settings, tree, bodies).node(0, 0, static_cast<std::uint32_t>(n), 0, false);

  // The bodies in tree order (padded for the leaf kernel), and the frame.
  tree.order.resize(n);
  for (auto* column : {&tree.sx, &tree.sy, &tree.sm}) column->assign(n + kLeafPadding, 0.0);
  double heaviest = 0.0;
  for (std::size_t r = 0; r < n; ++r) {
    const std::uint32_t i = bodies[r].index;
    tree.order[r] = i;
    tree.sx[r] = x[i];
    tree.sy[r] = y[i];
    tree.sm[r] = mass[i];
    heaviest = std::max(heaviest, mass[i]);
  }
  const double half = side * 0.5;
  tree.frame =
      detail::float_frame(tree.square.x0 + half, tree.square.y0 + half, half, heaviest, settings.G);
  tree.single = settings.single;
  if (tree.single) {
    tree.sm32.resize(n);
    float_masses(tree, 0, static_cast<std::uint32_t>(n));
  }

  // Moments: children come after their parent, so last node first.
  const CellGeometry cells(tree.square, settings.inv_theta);
  std::vector<Moments>& moments = scratch.moments;
  moments.resize(tree.nodes.size());
  (tree.single ? tree.node32.resize(tree.nodes.size() * kMoments)
               : tree.node64.resize(tree.nodes.size() * kMoments));
  for (std::size_t i = tree.nodes.size(); i-- > 0;) {
    Node& node = tree.nodes[i];
    std::uint64_t differ = 0;
    for (std::uint32_t r = node.begin + 1; r < node.end; ++r) {
      differ |= bodies[r].key ^ bodies[node.begin].key;
    }
    if (node.children == 0) {
      double sums[kLeafSums];
      build_kernels().leaf_moments(tree.sx.data(), tree.sy.data(), tree.sm.data(), &node.begin,
                                   &node.end, 1, sums);
      leaf_moments(sums, node, moments[i]);
    } else {
      moments[i] = Moments{};  // merge_moments adds to it
      merge_moments(tree.nodes.data(), moments.data(), node, moments[i]);
    }
    set_opening_radius(node, bodies[node.begin].key, shared_levels(differ), cells);
    kernel_moments(tree, i, moments[i]);
  }
}

}  // namespace calder::nbody::bh
