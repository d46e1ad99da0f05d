// SPDX-License-Identifier: MIT
// Barnes-Hut, the walk (Walker, barnes_hut_walk.cpp): per group, or unit of
// sibling groups, the walk of a built tree (barnes_hut_tree.hpp), the
// kernels' sums and the far field's interpolation, then the sums back to
// the caller's order. It reads the tree and writes only its own buffers.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "../claims.hpp"
#include "barnes_hut_tree.hpp"
#include "kernels.hpp"

namespace calder::nbody::bh {

// Columns of equal length that grow together (the interaction lists).
template <typename T, std::size_t K>
struct Columns {
  std::array<std::vector<T>, K> column;
  std::size_t size = 0;

  void clear() { size = 0; }
  // Room for `more` rows after size; returns the first free row.
  std::size_t make_room(std::size_t more) {
    if (size + more > column[0].size()) {
      const std::size_t capacity = std::max({size + more, 2 * column[0].size(), std::size_t{256}});
      for (auto& c : column) c.resize(capacity);
    }
    return size;
  }
  T* operator[](std::size_t k) { return column[k].data(); }
};

// Nodes as the multipole kernels read them: x, y, then the kMoments moments.
template <typename T>
using NodeColumns = Columns<T, detail::Nodes<T>::kColumns>;

// One group's interaction lists.
template <typename T>
struct Lists {
  Columns<T, 3> body;                 // x, y, m
  NodeColumns<T> node;                // accepted nodes
  NodeColumns<T> far;                 // the same, interpolated over the group
  std::vector<std::uint32_t> leaves;  // the leaves whose bodies are in body, in order
  Columns<T, 3> block_body;           // a block of targets' share of body
  NodeColumns<T> block_node;          // and the leaves its box accepts
  std::vector<T> tx;                  // float32 targets
  std::vector<T> ty;
};

// A group's bounding box and the origin of its float32 lists.
struct GroupFrame {
  double x0 = 0.0;
  double x1 = 0.0;
  double y0 = 0.0;
  double y1 = 0.0;
  double ox = 0.0;  // subtracted from positions, then scaled by `scale`
  double oy = 0.0;
  double scale = 1.0;
  // The interpolation square: centre and half side (0: no far list).
  double cx = 0.0;
  double cy = 0.0;
  double half = 0.0;
  double far2 = 0.0;  // nodes whose centre of mass is farther than sqrt(far2) from (cx, cy)
};

// A thread's lists and counts, on its own cache lines.
struct alignas(64) WalkScratch {
  Lists<double> lists64;
  Lists<float> lists32;
  Lists<double> unit64;  // a unit's far list
  Lists<float> unit32;
  std::vector<std::uint32_t> unit_near;    // nodes a unit accepts, not in its far list
  std::vector<std::uint32_t> unit_leaves;  // leaves a unit opens
  std::vector<std::uint32_t> stack;
  std::vector<double> prefix;       // running costs of the units
  std::vector<std::size_t> bounds;  // the shares' first units (share_bounds)
  std::uint64_t interactions = 0;
  std::uint64_t node_interactions = 0;
};

// What the walk needs of the options.
struct WalkSettings {
  double inv_theta = 0.0;        // 1 / theta, +inf for theta = 0
  std::size_t target_block = 0;  // float64: targets that re-test the opened leaves (0: none)
  int threads = 1;
};

class Walker {
 public:
  // (ax, ay) += factor * the sums over `tree` for law p (float32 lists in
  // `scale`), one parallel region; work[region * team + t] = thread t's work
  // in the walk's regions.
  void walk(const BuiltTree& tree, const WalkSettings& settings, const detail::LawParams& p,
            double scale, double factor, std::span<double> ax, std::span<double> ay,
            std::uint64_t* work);
  // The interactions of the last walk, all and with nodes.
  std::uint64_t interactions() const;
  std::uint64_t node_interactions() const;

 private:
  UnsetVector<double> sum_x_;  // sums in Morton order
  UnsetVector<double> sum_y_;
  std::vector<WalkScratch> scratch_;
  // Runs of groups with one parent (first group, count), walked together.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> units_;
  std::vector<double> unit_cost_;  // estimated (walk)
  std::vector<float> body_cost_;   // interactions per body of the last call, by caller's index
  calder::detail::Claims claims_;  // on the chunks of the walk's shares
  std::vector<std::uint64_t> chunk_work_;  // interactions of each chunk, by share
  WalkSettings settings_;
  const BuiltTree* tree_ = nullptr;  // the tree being walked (during walk)

  void scatter_share(std::size_t t, std::size_t nt, double factor, std::span<double> ax,
                     std::span<double> ay, std::uint64_t* work);
  void estimate_costs(std::size_t first, std::size_t last, bool history);
  void share_bounds(std::size_t nt, WalkScratch& s) const;
  void walk_units(std::size_t first, std::size_t last, const detail::LawParams& p, double scale,
                  WalkScratch& s);
  template <typename T>
  void walk_group(std::uint32_t group, WalkScratch& s, const detail::KernelTable& k,
                  const detail::LawParams& p, double scale);
  // The bodies' box; a far list beyond far_ratio / theta of its half sides.
  GroupFrame group_frame(const Node& g, bool float32, double scale, double far_ratio) const;
  GroupFrame bounding_box(std::uint32_t begin, std::uint32_t end) const;
  template <typename T>
  void collect(const GroupFrame& f, bool multipoles, WalkScratch& s, Lists<T>& lists);
  void plan_units();
  template <typename T>
  void walk_unit(std::uint32_t first, std::uint32_t count, WalkScratch& s,
                 const detail::KernelTable& k, const detail::LawParams& p, double scale);
  template <typename T>
  void add_node(const GroupFrame& f, std::uint32_t index, bool multipoles, Lists<T>& lists) const;
  template <typename T>
  void add_multipoles(const GroupFrame& f, std::uint32_t index, NodeColumns<T>& nodes) const;
  template <typename T>
  void add_leaf(const GroupFrame& f, std::uint32_t index, Lists<T>& lists) const;
  template <typename T>
  void sum_far(const Node& g, const GroupFrame& f, const detail::KernelTable& k,
               const detail::LawParams& p, Lists<T>& lists);
  template <typename T>
  void sum_leaves_by_block(const Node& g, const GroupFrame& f, const detail::KernelTable& k,
                           const detail::LawParams& p, WalkScratch& s, Lists<T>& lists, const T* tx,
                           const T* ty);
  template <typename T>
  void sum_group(const Node& g, const GroupFrame& f, const detail::KernelTable& k,
                 const detail::LawParams& p, WalkScratch& s, Lists<T>& lists);
};

}  // namespace calder::nbody::bh
