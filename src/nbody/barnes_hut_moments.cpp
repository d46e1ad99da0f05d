// SPDX-License-Identifier: MIT
// Barnes-Hut, the moments (barnes_hut_moments.hpp): leaves' from the build
// kernels' sums, inner nodes' from their children's, opening radii, and the
// moments as the multipole kernels read them (kernels.hpp: m, 3 Q, 1.5 tr Q,
// 7.5 O, 1.5 P, P = sum m s |s|^2), in float64 or scaled into the float32
// frame, with the bodies' masses for float32.
#include "barnes_hut_moments.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "barnes_hut_builder.hpp"
#include "common.hpp"

namespace calder::nbody::bh {

namespace {

// The kernel's kMoments numbers for one node's moments, scaled by powers of
// the frame's length and mass scales (1 for float64).
struct MomentScales {
  double mass = 1.0;
  double second = 1.0;  // length^2 mass
  double third = 1.0;   // length^3 mass
  double fourth = 1.0;  // length^4 mass
};

template <typename T>
void write_moments(const Moments& m, const MomentScales& s, T* o) {
  o[0] = static_cast<T>(m.mass * s.mass);
  o[1] = static_cast<T>(3.0 * m.qxx * s.second);
  o[2] = static_cast<T>(3.0 * m.qxy * s.second);
  o[3] = static_cast<T>(3.0 * m.qyy * s.second);
  o[4] = static_cast<T>(1.5 * (m.qxx + m.qyy) * s.second);
  o[5] = static_cast<T>(7.5 * m.oxxx * s.third);
  o[6] = static_cast<T>(7.5 * m.oxxy * s.third);
  o[7] = static_cast<T>(7.5 * m.oxyy * s.third);
  o[8] = static_cast<T>(7.5 * m.oyyy * s.third);
  o[9] = static_cast<T>(1.5 * (m.oxxx + m.oxyy) * s.third);
  o[10] = static_cast<T>(1.5 * (m.oxxy + m.oyyy) * s.third);
  o[11] = static_cast<T>(17.5 * m.hxxxx * s.fourth);
  o[12] = static_cast<T>(17.5 * m.hxxxy * s.fourth);
  o[13] = static_cast<T>(17.5 * m.hxxyy * s.fourth);
  o[14] = static_cast<T>(17.5 * m.hxyyy * s.fourth);
  o[15] = static_cast<T>(17.5 * m.hyyyy * s.fourth);
  o[16] = static_cast<T>(7.5 * (m.hxxxx + m.hxxyy) * s.fourth);
  o[17] = static_cast<T>(7.5 * (m.hxxxy + m.hxyyy) * s.fourth);
  o[18] = static_cast<T>(7.5 * (m.hxxyy + m.hyyyy) * s.fourth);
  o[19] = static_cast<T>(1.875 * (m.hxxxx + 2.0 * m.hxxyy + m.hyyyy) * s.fourth);
}

}  // namespace

CellGeometry::CellGeometry(const Square& square, double inv_theta_)
    : x0(square.x0), y0(square.y0), inv_theta(inv_theta_) {
  for (int level = 0; level <= kBits; ++level) {
    cell_size[static_cast<std::size_t>(level)] = std::ldexp(square.side, -level);
  }
}

void leaf_moments(const double* sums, Node& node, Moments& mo) {
  mo.mass = sums[kLeafMass];
  mo.qxx = sums[kLeafQxx];
  mo.qxy = sums[kLeafQxy];
  mo.qyy = sums[kLeafQyy];
  mo.oxxx = sums[kLeafOxxx];
  mo.oxxy = sums[kLeafOxxy];
  mo.oxyy = sums[kLeafOxyy];
  mo.oyyy = sums[kLeafOyyy];
  mo.hxxxx = sums[kLeafHxxxx];
  mo.hxxxy = sums[kLeafHxxxy];
  mo.hxxyy = sums[kLeafHxxyy];
  mo.hxyyy = sums[kLeafHxyyy];
  mo.hyyyy = sums[kLeafHyyyy];
  node.mx = sums[kLeafMx];
  node.my = sums[kLeafMy];
}

void merge_moments(const Node* nodes, const Moments* moments, Node& node, Moments& mo) {
  double mass = 0.0;
  double mx = 0.0;
  double my = 0.0;
  const std::uint32_t first = node.child;
  const std::uint32_t last = node.child + node.children;
  for (std::uint32_t c = first; c < last; ++c) {
    mass += moments[c].mass;
    mx += moments[c].mass * nodes[c].mx;
    my += moments[c].mass * nodes[c].my;
  }
  mx /= mass;
  my /= mass;
  for (std::uint32_t c = first; c < last; ++c) {
    // The child's moments about this centre of mass, the child's centre at
    // offset (dx, dy): s = d + s', sum m s' = 0.
    const Moments& m = moments[c];
    const double dx = nodes[c].mx - mx;
    const double dy = nodes[c].my - my;
    mo.qxx += m.qxx + m.mass * dx * dx;
    mo.qxy += m.qxy + m.mass * dx * dy;
    mo.qyy += m.qyy + m.mass * dy * dy;
    mo.oxxx += m.oxxx + 3.0 * dx * m.qxx + m.mass * dx * dx * dx;
    mo.oxxy += m.oxxy + 2.0 * dx * m.qxy + dy * m.qxx + m.mass * dx * dx * dy;
    mo.oxyy += m.oxyy + 2.0 * dy * m.qxy + dx * m.qyy + m.mass * dx * dy * dy;
    mo.oyyy += m.oyyy + 3.0 * dy * m.qyy + m.mass * dy * dy * dy;
    const double xx = dx * dx;
    const double xy = dx * dy;
    const double yy = dy * dy;
    mo.hxxxx += m.hxxxx + 4.0 * dx * m.oxxx + 6.0 * xx * m.qxx + m.mass * xx * xx;
    mo.hxxxy += m.hxxxy + 3.0 * dx * m.oxxy + dy * m.oxxx + 3.0 * (xx * m.qxy + xy * m.qxx) +
                m.mass * xx * xy;
    mo.hxxyy += m.hxxyy + 2.0 * (dx * m.oxyy + dy * m.oxxy) + xx * m.qyy + 4.0 * xy * m.qxy +
                yy * m.qxx + m.mass * xx * yy;
    mo.hxyyy += m.hxyyy + 3.0 * dy * m.oxyy + dx * m.oyyy + 3.0 * (yy * m.qxy + xy * m.qyy) +
                m.mass * xy * yy;
    mo.hyyyy += m.hyyyy + 4.0 * dy * m.oyyy + 6.0 * yy * m.qyy + m.mass * yy * yy;
  }
  mo.mass = mass;
  node.mx = mx;
  node.my = my;
}

// Accepted beyond size / theta + delta from the centre of mass, delta its
// distance to the cell's centre.
void set_opening_radius(Node& node, std::uint64_t key, int level, const CellGeometry& cells) {
  const double size = cells.cell_size[static_cast<std::size_t>(level)];
  const double cx = cells.x0 + (static_cast<double>(compact(key) >> (kBits - level)) + 0.5) * size;
  const double cy =
      cells.y0 + (static_cast<double>(compact(key >> 1) >> (kBits - level)) + 0.5) * size;
  const double delta = std::sqrt((node.mx - cx) * (node.mx - cx) + (node.my - cy) * (node.my - cy));
  const double open = size * cells.inv_theta + delta;
  node.open2 = open * open;
}

void kernel_moments(BuiltTree& tree, std::size_t i, const Moments& moments) {
  if (!tree.single) {
    write_moments(moments, MomentScales{}, tree.node64.data() + i * kMoments);
    return;
  }
  const detail::FloatFrame& frame = tree.frame;
  const double second = frame.scale * frame.scale * frame.mass_scale;
  write_moments(moments,
                MomentScales{frame.mass_scale, second, second * frame.scale,
                             second * frame.scale * frame.scale},
                tree.node32.data() + i * kMoments);
}

void float_masses(BuiltTree& tree, std::uint32_t begin, std::uint32_t end) {
  for (std::uint32_t r = begin; r < end; ++r) {
    tree.sm32[r] = static_cast<float>(tree.sm[r] * tree.frame.mass_scale);
  }
}

// The fast build's side (barnes_hut_builder.hpp).

// Mass, centre of mass and moments of inner node `index` from its children's
// (which must be finished), and its opening radius.
void TreeBuilder::finish_node(Node* nodes, Moments* moments, std::uint32_t index,
                              const SortedKeys& sorted) const {
  Node& node = nodes[index];
  Moments mo{};
  merge_moments(nodes, moments, node, mo);
  moments[index] = mo;
  opening_radius(node, sorted);
}

// The moments and opening radii of a part that build_node made: its leaves'
// from their bodies (the build kernels), then its inner nodes' from their
// children, last node first (a node's children come after it).
void TreeBuilder::finish_part(Tree& t, const SortedKeys& sorted, BuildScratch& buffers) const {
  buffers.leaf_node.clear();
  buffers.leaf_begin.clear();
  buffers.leaf_end.clear();
  for (std::size_t i = 0; i < t.nodes.size(); ++i) {
    if (t.nodes[i].children != 0) continue;
    buffers.leaf_node.push_back(static_cast<std::uint32_t>(i));
    buffers.leaf_begin.push_back(t.nodes[i].begin);
    buffers.leaf_end.push_back(t.nodes[i].end);
  }
  const std::size_t leaves = buffers.leaf_node.size();
  buffers.leaf_sums.resize(leaves * kLeafSums);
  build_kernels().leaf_moments(out_->sx.data(), out_->sy.data(), out_->sm.data(),
                               buffers.leaf_begin.data(), buffers.leaf_end.data(), leaves,
                               buffers.leaf_sums.data());
  for (std::size_t k = 0; k < leaves; ++k) {
    Node& node = t.nodes[buffers.leaf_node[k]];
    leaf_moments(buffers.leaf_sums.data() + kLeafSums * k, node, t.moments[buffers.leaf_node[k]]);
    opening_radius(node, sorted);
  }
  for (std::size_t i = t.nodes.size(); i-- > 0;) {
    if (t.nodes[i].children != 0) {
      finish_node(t.nodes.data(), t.moments.data(), static_cast<std::uint32_t>(i), sorted);
    }
  }
}

// The cell: level `level` of the root square, found from the common prefix.
void TreeBuilder::opening_radius(Node& node, const SortedKeys& sorted) const {
  const int level = node.children == 0 ? leaf_level(node.begin, node.end, sorted)
                                       : level_of(node.begin, node.end, sorted);
  set_opening_radius(node, sorted[node.begin], level, cells_);
}

}  // namespace calder::nbody::bh
