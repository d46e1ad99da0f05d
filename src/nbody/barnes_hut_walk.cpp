// SPDX-License-Identifier: MIT
// Barnes-Hut, the walk: per group (a node of <= group_size bodies), one walk
// from the root; an accepted node goes to the node list (centre of mass,
// mass, moments; for the clamped laws a point mass: those laws are not
// harmonic, so their multipole expansion is not Newton's), or to the far
// list when it is far from the group, the bodies of an opened leaf to the
// body list. The kernels then sum the node and body lists for all the
// group's bodies, and the far list at a few points of the group's square,
// interpolated to the bodies; float32 lists are relative to the group's
// centre. Groups that share a parent form a unit (walk_unit): one walk from
// the root for all of them, its far list summed once for all their bodies,
// each group's walk continued from what the unit left open. Units go to
// threads in runs of equal estimated cost (walk), cut in chunks that a
// thread done with its own run takes from the others' (src/claims.hpp); each
// body's sum is made by one thread in a fixed order, so the results do not
// depend on the number of threads or on which thread walked which unit.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "barnes_hut_walker.hpp"
#include "calder/detmath.hpp"

namespace calder::nbody::bh {

namespace {
// The far field of a group: the accepted nodes whose centre of mass lies
// beyond kFarRatio / theta half sides of the group's square from its centre
// are summed at kStencil x kStencil points and interpolated (sum_far). The
// interpolation's error falls with that distance as the multipole
// expansion's falls with theta, so it stays below it at every theta (none at
// theta 0, the direct sum): at the default, 0.7, the ratio is 4 half sides,
// where it adds little (N = 10^6 disk: RMS 6.4e-4; with a ratio of 1.8 /
// theta, 2.6 half sides there, 2.6e-3: with nodes to fourth order the
// interpolation's error shows first when the far field comes nearer).
constexpr std::size_t kStencil = detail::kFarStencil;
constexpr double kFarRatio = 2.8;
// A unit's far list (walk_unit): its square is about twice a group's, and
// beyond kUnitFarRatio / theta of its half sides (6 at theta 0.7) its
// interpolation adds less error than the groups'.
constexpr double kUnitFarRatio = 4.2;
// Groups of at most this many bodies sum every node at each target (the
// stencil would cost about as much).
constexpr std::size_t kFarMinTargets = 32;

// The Chebyshev points on [-1, 1] and the Lagrange basis' weights
// 1 / prod_{j != i} (u_i - u_j).
struct Stencil {
  double u[kStencil];
  double weight[kStencil];
};
const Stencil& stencil() {
  static const Stencil s = [] {
    Stencil t{};
    constexpr double kPi = 3.141592653589793;
    for (std::size_t i = 0; i < kStencil; ++i) {
      t.u[i] = math::cos((2.0 * static_cast<double>(i) + 1.0) * kPi / (2.0 * kStencil));
    }
    for (std::size_t i = 0; i < kStencil; ++i) {
      double d = 1.0;
      for (std::size_t j = 0; j < kStencil; ++j) {
        if (j != i) d *= t.u[i] - t.u[j];
      }
      t.weight[i] = 1.0 / d;
    }
    return t;
  }();
  return s;
}

// The walk's lambdas must be inlined into its loop.
#define CALDER_BH_INLINE __attribute__((always_inline))

// Whether the group of frame f accepts node n: Barnes' criterion, the
// distance measured from the group's box.
[[gnu::always_inline]] inline bool accepts(const Node& n, const GroupFrame& f) {
  const double dx = std::max(std::max(f.x0 - n.mx, n.mx - f.x1), 0.0);
  const double dy = std::max(std::max(f.y0 - n.my, n.my - f.y1), 0.0);
  return dx * dx + dy * dy > n.open2;
}

// Whether an accepted node n belongs to the far field of frame f's square.
[[gnu::always_inline]] inline bool is_far(const Node& n, const GroupFrame& f) {
  const double ex = n.mx - f.cx;
  const double ey = n.my - f.cy;
  return f.far2 > 0.0 && ex * ex + ey * ey > f.far2;
}

// The walk from the root for frame f: `accepted(index)` for each node it
// accepts, `leaf(index)` for each leaf it opens, children in order.
template <class Accepted, class Leaf>
[[gnu::always_inline]] inline void visit(const UnsetVector<Node>& nodes, const GroupFrame& f,
                                         std::vector<std::uint32_t>& stack, Accepted accepted,
                                         Leaf leaf) {
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const std::uint32_t index = stack.back();
    stack.pop_back();
    const Node& n = nodes[index];
    if (accepts(n, f)) {
      accepted(index);
    } else if (n.children == 0) {
      leaf(index);
    } else {
      for (std::uint32_t c = n.child + n.children; c-- > n.child;) stack.push_back(c);
    }
  }
}
}  // namespace

// Units go to threads in contiguous runs (shares) of about equal estimated
// cost (the runs of Morton order keep each thread's bodies together). A
// unit's cost: the interactions per body that the last call measured for
// its bodies (by the caller's index: bodies move little between steps), or
// 1 a body on a first call or when the number of bodies changed. The shares
// depend on the calls' inputs only, never on timing, and so does the work
// counted for each (work[walk][t]: share t's); a thread that finishes its
// share early walks the last chunks of the others' that are not started.
void Walker::walk(const BuiltTree& tree, const WalkSettings& settings, const detail::LawParams& p,
                  double scale, double factor, std::span<double> ax, std::span<double> ay,
                  std::uint64_t* work) {
  tree_ = &tree;
  settings_ = settings;
  const int threads = settings.threads;
  const std::size_t n = tree.order.size();
  sum_x_.resize(n);  // zeroed group by group
  sum_y_.resize(n);
  scratch_.resize(static_cast<std::size_t>(threads));
  for (auto& s : scratch_) s.interactions = s.node_interactions = 0;
  plan_units();
  unit_cost_.resize(units_.size());
  const bool history = body_cost_.size() == n;
  body_cost_.resize(n);
  const auto nt = static_cast<std::size_t>(team_for(n, threads));
  constexpr std::size_t kChunks = calder::detail::kChunksPerShare;
  claims_.reset(nt, kChunks);
  chunk_work_.assign(nt * kChunks, 0);
#if defined(_OPENMP)
#pragma omp parallel num_threads(static_cast <int>(nt))
#endif
  {
    const std::size_t t = calder::detail::team_thread();
    WalkScratch& s = scratch_[t];
    estimate_costs(units_.size() * t / nt, units_.size() * (t + 1) / nt, history);
#if defined(_OPENMP)
#pragma omp barrier
#endif
    share_bounds(nt, s);
    std::size_t share = 0;
    std::uint32_t chunk = 0;
    while (claims_.next(t, share, chunk)) {
      const auto [begin, end] =
          calder::detail::chunk_of(s.bounds[share], s.bounds[share + 1] - s.bounds[share], chunk);
      const std::uint64_t before = s.interactions;
      walk_units(begin, end, p, scale, s);
      chunk_work_[share * kChunks + chunk] = s.interactions - before;
    }
#if defined(_OPENMP)
#pragma omp barrier
#endif
    scatter_share(t, nt, factor, ax, ay, work);
  }
  for (std::size_t t = 0; t < nt; ++t) {
    std::uint64_t share = 0;
    for (std::size_t c = 0; c < kChunks; ++c) share += chunk_work_[t * kChunks + c];
    work[kRegionWalk * nt + t] = share;
  }
  tree_ = nullptr;
}

std::uint64_t Walker::interactions() const {
  std::uint64_t all = 0;
  for (const WalkScratch& s : scratch_) all += s.interactions;
  return all;
}

std::uint64_t Walker::node_interactions() const {
  std::uint64_t all = 0;
  for (const WalkScratch& s : scratch_) all += s.node_interactions;
  return all;
}

// Thread t's part of (ax, ay) += factor * the sums, from Morton order back
// to the caller's (a permutation: no two ranks write one body). The writes
// land at random: the team splits the 2n writes (ax's ranks, then ay's) in
// equal slices, so that each thread writes one component over a run of
// ranks (two at most) and two threads rarely write one cache line.
void Walker::scatter_share(std::size_t t, std::size_t nt, double factor, std::span<double> ax,
                           std::span<double> ay, std::uint64_t* work) {
  const UnsetVector<std::uint32_t>& order = tree_->order;
  const std::size_t n = order.size();
  const std::size_t lo = 2 * n * t / nt;
  const std::size_t hi = 2 * n * (t + 1) / nt;
  for (std::size_t u = lo; u < std::min(hi, n); ++u) ax[order[u]] += factor * sum_x_[u];
  for (std::size_t u = std::max(lo, n); u < hi; ++u) ay[order[u - n]] += factor * sum_y_[u - n];
  work[kRegionScatter * nt + t] = hi - lo;
}

// Units [first, last)'s estimated costs.
void Walker::estimate_costs(std::size_t first, std::size_t last, bool history) {
  for (std::size_t u = first; u < last; ++u) {
    const auto [g, count] = units_[u];
    const std::uint32_t begin = tree_->nodes[tree_->groups[g]].begin;
    const std::uint32_t end = tree_->nodes[tree_->groups[g + count - 1]].end;
    double cost = 0.0;
    if (history) {
      for (std::uint32_t r = begin; r < end; ++r)
        cost += static_cast<double>(body_cost_[tree_->order[r]]);
    }
    unit_cost_[u] = history ? cost : static_cast<double>(end - begin);
  }
}

// The shares' runs of units (every thread works them out alike): share k
// is [bounds[k], bounds[k + 1]), from where the running cost passes k / nt
// of the total.
void Walker::share_bounds(std::size_t nt, WalkScratch& s) const {
  s.prefix.resize(unit_cost_.size() + 1);
  s.prefix[0] = 0.0;
  for (std::size_t u = 0; u < unit_cost_.size(); ++u) s.prefix[u + 1] = s.prefix[u] + unit_cost_[u];
  const double total = s.prefix.back();
  const auto at = [&](std::size_t k) {  // the first unit whose middle lies past k / nt of the total
    const double mark = total * static_cast<double>(k) / static_cast<double>(nt);
    std::size_t u = 0;
    std::size_t hi = unit_cost_.size();
    while (u < hi) {
      const std::size_t mid = (u + hi) / 2;
      if (s.prefix[mid] + 0.5 * unit_cost_[mid] < mark) {
        u = mid + 1;
      } else {
        hi = mid;
      }
    }
    return k == nt ? unit_cost_.size() : u;
  };
  s.bounds.resize(nt + 1);
  for (std::size_t k = 0; k <= nt; ++k) s.bounds[k] = at(k);
}

// Walks units [first, last) and records their bodies' interactions.
void Walker::walk_units(std::size_t first, std::size_t last, const detail::LawParams& p,
                        double scale, WalkScratch& s) {
  const detail::KernelTable& k = detail::kernels();
  const bool multipoles = p.law == Law::plummer;
  for (std::size_t u = first; u < last; ++u) {
    const auto [g0, groups] = units_[u];
    const std::uint64_t before = s.interactions;
    if (multipoles && groups > 1) {
      if (tree_->single) {
        walk_unit<float>(g0, groups, s, k, p, scale);
      } else {
        walk_unit<double>(g0, groups, s, k, p, scale);
      }
    } else {
      for (std::uint32_t g = g0; g < g0 + groups; ++g) {
        if (tree_->single) {
          walk_group<float>(tree_->groups[g], s, k, p, scale);
        } else {
          walk_group<double>(tree_->groups[g], s, k, p, scale);
        }
      }
    }
    const std::uint32_t begin = tree_->nodes[tree_->groups[g0]].begin;
    const std::uint32_t end = tree_->nodes[tree_->groups[g0 + groups - 1]].end;
    const auto per_body = static_cast<float>(static_cast<double>(s.interactions - before) /
                                             static_cast<double>(end - begin));
    for (std::uint32_t r = begin; r < end; ++r) body_cost_[tree_->order[r]] = per_body;
  }
}

// Units: runs of consecutive groups (in walk order) that share a parent
// (parents from the build).
void Walker::plan_units() {
  constexpr std::uint32_t kNone = ~std::uint32_t{0};
  units_.clear();
  const auto groups = static_cast<std::uint32_t>(tree_->groups.size());
  for (std::uint32_t g = 0; g < groups;) {
    const std::uint32_t up = tree_->parent[tree_->groups[g]];
    std::uint32_t end = g + 1;
    while (end < groups && up != kNone && tree_->parent[tree_->groups[end]] == up) ++end;
    units_.emplace_back(g, end - g);
    g = end;
  }
}

// A unit of groups: one walk for their common box; the accepted nodes far
// from it summed once on its stencil (sum_far) for all its bodies; each group
// then starts from what the unit accepted nearer and the leaves it opened.
template <typename T>
void Walker::walk_unit(std::uint32_t first, std::uint32_t count, WalkScratch& s,
                       const detail::KernelTable& k, const detail::LawParams& p, double scale) {
  constexpr bool kFloat = sizeof(T) == 4;
  Lists<T>* lists;
  Lists<T>* unit_lists;
  if constexpr (kFloat) {
    lists = &s.lists32;
    unit_lists = &s.unit32;
  } else {
    lists = &s.lists64;
    unit_lists = &s.unit64;
  }
  Node unit{};
  unit.begin = tree_->nodes[tree_->groups[first]].begin;
  unit.end = tree_->nodes[tree_->groups[first + count - 1]].end;
  const GroupFrame fu = group_frame(unit, kFloat, scale, kUnitFarRatio);
  unit_lists->far.clear();
  s.unit_near.clear();
  s.unit_leaves.clear();
  visit(
      tree_->nodes, fu, s.stack,
      [&](std::uint32_t index) CALDER_BH_INLINE {
        if (is_far(tree_->nodes[index], fu)) {
          add_node(fu, index, true, *unit_lists);
        } else {
          s.unit_near.push_back(index);
        }
      },
      [&](std::uint32_t index) CALDER_BH_INLINE { s.unit_leaves.push_back(index); });
  for (std::uint32_t g = first; g < first + count; ++g) {
    const Node& group = tree_->nodes[tree_->groups[g]];
    const GroupFrame f = group_frame(group, kFloat, scale, kFarRatio);
    lists->body.clear();
    lists->node.clear();
    lists->far.clear();
    lists->leaves.clear();
    for (const std::uint32_t index : s.unit_near) add_node(f, index, true, *lists);
    for (const std::uint32_t index : s.unit_leaves) {
      if (accepts(tree_->nodes[index], f)) {
        add_node(f, index, true, *lists);
      } else {
        add_leaf(f, index, *lists);
      }
    }
    sum_group(group, f, k, p, s, *lists);
  }
  if (unit_lists->far.size > 0) {
    sum_far(unit, fu, k, p, *unit_lists);
    s.interactions += kStencil * kStencil * unit_lists->far.size;
    s.node_interactions += kStencil * kStencil * unit_lists->far.size;
  }
}

// Node `index`, accepted, into the lists of the group of frame f: its
// multipoles to the near or the far list, or (multipoles false) its mass to
// the body list.
template <typename T>
void Walker::add_node(const GroupFrame& f, std::uint32_t index, bool multipoles,
                      Lists<T>& lists) const {
  const Node& n = tree_->nodes[index];
  if (multipoles) {
    add_multipoles(f, index, is_far(n, f) ? lists.far : lists.node);
    return;
  }
  const std::size_t r = lists.body.make_room(1);  // a point mass
  lists.body[0][r] = static_cast<T>((n.mx - f.ox) * f.scale);
  lists.body[1][r] = static_cast<T>((n.my - f.oy) * f.scale);
  if constexpr (sizeof(T) == 4) {
    lists.body[2][r] = tree_->node32[std::size_t{index} * kMoments];
  } else {
    lists.body[2][r] = tree_->node64[std::size_t{index} * kMoments];
  }
  lists.body.size = r + 1;
}

// Node `index`'s centre (in frame f) and moments, a row of `nodes`.
template <typename T>
void Walker::add_multipoles(const GroupFrame& f, std::uint32_t index, NodeColumns<T>& nodes) const {
  const Node& n = tree_->nodes[index];
  const T* m;
  if constexpr (sizeof(T) == 4) {
    m = tree_->node32.data() + std::size_t{index} * kMoments;
  } else {
    m = tree_->node64.data() + std::size_t{index} * kMoments;
  }
  const std::size_t r = nodes.make_room(1);
  nodes[0][r] = static_cast<T>((n.mx - f.ox) * f.scale);
  nodes[1][r] = static_cast<T>((n.my - f.oy) * f.scale);
  for (std::size_t a = 0; a < kMoments; ++a) nodes[2 + a][r] = m[a];
  nodes.size = r + 1;
}

// The bodies of leaf `index` into the body list of the group of frame f.
template <typename T>
void Walker::add_leaf(const GroupFrame& f, std::uint32_t index, Lists<T>& lists) const {
  const Node& n = tree_->nodes[index];
  lists.leaves.push_back(index);
  auto& body = lists.body;
  const std::size_t count = n.end - n.begin;
  const std::size_t r = body.make_room(count);
  if constexpr (sizeof(T) == 4) {
    for (std::size_t b = 0; b < count; ++b) {
      body[0][r + b] = static_cast<T>((tree_->sx[n.begin + b] - f.ox) * f.scale);
      body[1][r + b] = static_cast<T>((tree_->sy[n.begin + b] - f.oy) * f.scale);
    }
    std::memcpy(body[2] + r, tree_->sm32.data() + n.begin, count * sizeof(T));
  } else {
    std::memcpy(body[0] + r, tree_->sx.data() + n.begin, count * sizeof(T));
    std::memcpy(body[1] + r, tree_->sy.data() + n.begin, count * sizeof(T));
    std::memcpy(body[2] + r, tree_->sm.data() + n.begin, count * sizeof(T));
  }
  body.size = r + count;
}

template <typename T>
void Walker::walk_group(std::uint32_t group, WalkScratch& s, const detail::KernelTable& k,
                        const detail::LawParams& p, double scale) {
  constexpr bool kFloat = sizeof(T) == 4;
  const Node& g = tree_->nodes[group];
  const GroupFrame f = group_frame(g, kFloat, scale, kFarRatio);
  Lists<T>* lists;
  if constexpr (kFloat) {
    lists = &s.lists32;
  } else {
    lists = &s.lists64;
  }
  collect(f, p.law == Law::plummer, s, *lists);
  sum_group(g, f, k, p, s, *lists);
}

// The group's bounding box; float32 lists are relative to its centre, in
// the frame's scale.
GroupFrame Walker::group_frame(const Node& g, bool float32, double scale, double far_ratio) const {
  GroupFrame f = bounding_box(g.begin, g.end);
  if (float32) {
    f.ox = f.x0 + (f.x1 - f.x0) * 0.5;
    f.oy = f.y0 + (f.y1 - f.y0) * 0.5;
    f.scale = scale;
  }
  if (g.end - g.begin > kFarMinTargets) {
    f.cx = f.x0 + (f.x1 - f.x0) * 0.5;
    f.cy = f.y0 + (f.y1 - f.y0) * 0.5;
    f.half = 0.5 * std::max(f.x1 - f.x0, f.y1 - f.y0);
    const double r = far_ratio * settings_.inv_theta * f.half;  // +inf at theta 0: no far list
    f.far2 = f.half > 0.0 ? r * r : 0.0;
  }
  return f;
}

// The bounding box of bodies [begin, end) (a frame with no far list, no
// float32 origin).
GroupFrame Walker::bounding_box(std::uint32_t begin, std::uint32_t end) const {
  GroupFrame f;
  f.x0 = f.x1 = tree_->sx[begin];
  f.y0 = f.y1 = tree_->sy[begin];
  for (std::uint32_t b = begin + 1; b < end; ++b) {
    f.x0 = std::min(f.x0, tree_->sx[b]);
    f.x1 = std::max(f.x1, tree_->sx[b]);
    f.y0 = std::min(f.y0, tree_->sy[b]);
    f.y1 = std::max(f.y1, tree_->sy[b]);
  }
  return f;
}

// The walk from the root: accepted nodes to the node list (multipoles) or
// the body list (point masses), the bodies of opened leaves to the body list.
template <typename T>
void Walker::collect(const GroupFrame& f, bool multipoles, WalkScratch& s, Lists<T>& lists) {
  lists.body.clear();
  lists.node.clear();
  lists.far.clear();
  lists.leaves.clear();
  visit(
      tree_->nodes, f, s.stack,
      [&](std::uint32_t index) CALDER_BH_INLINE { add_node(f, index, multipoles, lists); },
      [&](std::uint32_t index) CALDER_BH_INLINE { add_leaf(f, index, lists); });
}

// The far nodes' field, evaluated at kStencil x kStencil Chebyshev points of
// the group's square and interpolated (a tensor product of Lagrange
// polynomials of degree kStencil - 1) at each target: kStencil^2 node sums
// instead of one per target.
template <typename T>
void Walker::sum_far(const Node& g, const GroupFrame& f, const detail::KernelTable& k,
                     const detail::LawParams& p, Lists<T>& lists) {
  constexpr std::size_t S = kStencil;
  const Stencil& st = stencil();
  const auto& nodes_u = st.u;
  T px[S * S];
  T py[S * S];
  for (std::size_t i = 0; i < S; ++i) {
    for (std::size_t j = 0; j < S; ++j) {
      px[i * S + j] = static_cast<T>((f.cx + f.half * nodes_u[i] - f.ox) * f.scale);
      py[i * S + j] = static_cast<T>((f.cy + f.half * nodes_u[j] - f.oy) * f.scale);
    }
  }
  double fx[S * S] = {};
  double fy[S * S] = {};
  detail::Nodes<T> far;
  for (std::size_t c = 0; c < detail::Nodes<T>::kColumns; ++c) far.column[c] = lists.far[c];
  far.n = lists.far.size;
  if constexpr (sizeof(T) == 4) {
    k.multipole32(px, py, S * S, far, p, fx, fy);
  } else {
    k.multipole64(px, py, S * S, far, p, fx, fy);
  }
  // Per target (a kernel, over vectors of targets): the Lagrange basis at its
  // (u, v) in the square, the values contracted along v, then along u.
  const detail::FarField field{f.cx, f.cy, 1.0 / f.half, st.u, st.weight, fx, fy};
  k.interpolate_far(tree_->sx.data() + g.begin, tree_->sy.data() + g.begin, g.end - g.begin, field,
                    sum_x_.data() + g.begin, sum_y_.data() + g.begin);
}

// Each target of the group: the far field, the accepted nodes (in walk
// order), then the bodies, into sum_x, sum_y.
template <typename T>
void Walker::sum_group(const Node& g, const GroupFrame& f, const detail::KernelTable& k,
                       const detail::LawParams& p, WalkScratch& s, Lists<T>& lists) {
  const std::size_t count = g.end - g.begin;
  auto& body = lists.body;
  auto& accepted = lists.node;
  // Float64 sums the Plummer law's opened leaves block by block where asked
  // (target_block; the clamped laws' body list also holds the accepted
  // nodes' point masses). Float32 pairs are cheap enough that the blocks'
  // lists cost more than they save.
  const bool by_block = sizeof(T) == 8 && p.law == Law::plummer && settings_.target_block > 0 &&
                        count > settings_.target_block;
  const std::size_t far_rows = lists.far.size > 0 ? kStencil * kStencil : 0;
  s.interactions +=
      static_cast<std::uint64_t>(count) * (accepted.size + (by_block ? 0 : body.size)) +
      far_rows * lists.far.size;
  s.node_interactions +=
      static_cast<std::uint64_t>(count) * accepted.size + far_rows * lists.far.size;
  double* out_x = sum_x_.data() + g.begin;
  double* out_y = sum_y_.data() + g.begin;
  std::fill(out_x, out_x + count, 0.0);
  std::fill(out_y, out_y + count, 0.0);
  detail::Nodes<T> node_list;
  for (std::size_t c = 0; c < detail::Nodes<T>::kColumns; ++c) node_list.column[c] = accepted[c];
  node_list.n = accepted.size;
  const detail::Bodies<T> body_list{body[0], body[1], body[2], body.size};
  if constexpr (sizeof(T) == 4) {
    lists.tx.resize(count);
    lists.ty.resize(count);
    for (std::size_t t = 0; t < count; ++t) {
      lists.tx[t] = static_cast<T>((tree_->sx[g.begin + t] - f.ox) * f.scale);
      lists.ty[t] = static_cast<T>((tree_->sy[g.begin + t] - f.oy) * f.scale);
    }
    const T* tx = lists.tx.data();
    const T* ty = lists.ty.data();
    if (lists.far.size > 0) sum_far(g, f, k, p, lists);
    if (node_list.n > 0) k.multipole32(tx, ty, count, node_list, p, out_x, out_y);
    k.group32(tx, ty, nullptr, nullptr, count, body_list, p, out_x, out_y);
  } else {
    const T* tx = tree_->sx.data() + g.begin;
    const T* ty = tree_->sy.data() + g.begin;
    if (lists.far.size > 0) sum_far(g, f, k, p, lists);
    if (node_list.n > 0) k.multipole64(tx, ty, count, node_list, p, out_x, out_y);
    if (by_block) {
      sum_leaves_by_block(g, f, k, p, s, lists, tx, ty);
    } else {
      k.group64(tx, ty, count, body_list, p, out_x, out_y);
    }
  }
}

// The group's walk opens every leaf near any of its bodies. For each block
// of target_block consecutive targets (a compact patch: they are in Morton
// order), the leaves (lists.leaves, their bodies in lists.body) that the
// block's own box accepts are summed as multipoles, the others' bodies as
// pairs.
template <typename T>
void Walker::sum_leaves_by_block(const Node& g, const GroupFrame& f, const detail::KernelTable& k,
                                 const detail::LawParams& p, WalkScratch& s, Lists<T>& lists,
                                 const T* tx, const T* ty) {
  const std::size_t count = g.end - g.begin;
  auto& block_body = lists.block_body;
  auto& block_node = lists.block_node;
  for (std::size_t first = 0; first < count; first += settings_.target_block) {
    const std::size_t targets = std::min(settings_.target_block, count - first);
    const auto begin = g.begin + static_cast<std::uint32_t>(first);
    const GroupFrame box = bounding_box(begin, begin + static_cast<std::uint32_t>(targets));
    block_body.clear();
    block_node.clear();
    std::size_t row = 0;  // the leaf's first row in lists.body
    for (const std::uint32_t index : lists.leaves) {
      const Node& n = tree_->nodes[index];
      const std::size_t bodies = n.end - n.begin;
      if (accepts(n, box)) {
        add_multipoles(f, index, block_node);
      } else {
        const std::size_t r = block_body.make_room(bodies);
        for (std::size_t c = 0; c < 3; ++c) {
          std::memcpy(block_body[c] + r, lists.body[c] + row, bodies * sizeof(T));
        }
        block_body.size = r + bodies;
      }
      row += bodies;
    }
    s.interactions += static_cast<std::uint64_t>(targets) * (block_body.size + block_node.size);
    s.node_interactions += static_cast<std::uint64_t>(targets) * block_node.size;
    double* out_x = sum_x_.data() + begin;
    double* out_y = sum_y_.data() + begin;
    detail::Nodes<T> node_list;
    for (std::size_t c = 0; c < detail::Nodes<T>::kColumns; ++c) {
      node_list.column[c] = block_node[c];
    }
    node_list.n = block_node.size;
    const detail::Bodies<T> body_list{block_body[0], block_body[1], block_body[2], block_body.size};
    if (node_list.n > 0) k.multipole64(tx + first, ty + first, targets, node_list, p, out_x, out_y);
    k.group64(tx + first, ty + first, targets, body_list, p, out_x, out_y);
  }
}

}  // namespace calder::nbody::bh
