#pragma once
/// @file patch_lattice.hpp
/// A patch of the time loop's model on its lattice (docs/wheel-rail.md §9): the state a
/// patch keeps from one call to the next, its frame and grid placed by whole elements from
/// the anchor where it appeared (a box kept while the patch stays inside it), and its
/// predecessors' contact sets mapped onto its grid as the next solve's start.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "fastnorm/grid.hpp"
#include "fastnorm/wheelrail/contact_search.hpp"
#include "fastnorm/wheelrail/patch.hpp"
#include "fastnorm/wheelrail/track.hpp"

namespace fastnorm::wheelrail::detail {

inline constexpr std::size_t no_solver = static_cast<std::size_t>(-1);

/// A patch's state kept from one call to the next.
template <typename Workspace>
struct PatchState {
  PatchFrame frame;               ///< the grid's frame
  PatchFrame anchor;              ///< the lattice's origin: the frame where the patch appeared
  Eigen::Vector3d centre;         ///< the contact reference point (matching)
  /// The grid on the lattice: its element (0, 0) is lattice point (box_i, box_j) from the
  /// anchor, in elements; while the patch stays inside, the box (and so the numbering of
  /// the elements, the solver and the workspace's start) is kept.
  Eigen::Index box_i = 0, box_j = 0;
  Grid<double> grid{1, 1, 1, 1};
  std::vector<Eigen::Index> contact_set;
  /// The model's solver of the grid's size, whose storage `workspace` holds; `no_solver`
  /// once the workspace has moved on.
  std::size_t solver = no_solver;
  Workspace workspace;
};

/// Elements added at least on every side when a patch needs a new box.
inline constexpr Eigen::Index box_margin = 2;
/// A new box's sides are multiples of this many elements, so that a run meets few grid
/// sizes (each a solver with its tables and caches): 58 sizes became 12 along the
/// trajectory benchmark (docs/performance.md §8).
inline constexpr Eigen::Index box_quantum = 8;

/// The frame and grid of the patch of `region` (elements dx × ds, m), into `state`. On the
/// lattice, the frame's origin is the anchor (where the patch appeared) moved by whole
/// elements towards the new reference point, and the grid keeps its only predecessor's box
/// while the patch's extent stays inside it; off the lattice, the grid is centred on the
/// reference point.
template <typename State>
void place_grid(const Track& track, const ContactRegion& region, const std::vector<std::size_t>& predecessors,
                const std::vector<State>& previous, double dx, double ds, bool on_lattice, State& state) {
  state.frame = patch_frame(track, region);
  state.centre = region.centre;
  if (!on_lattice) {
    state.grid = patch_grid(patch_extent(state.frame, region), dx, ds);
    return;
  }
  const State* kept = predecessors.size() == 1 ? &previous[predecessors.front()] : nullptr;
  state.anchor = predecessors.empty() ? state.frame : previous[predecessors.front()].anchor;
  const Eigen::Vector3d along = state.anchor.lateral_axis();
  const Eigen::Vector3d offset = region.centre - state.anchor.reference;
  const double a = std::round(offset.x() / dx), b = std::round(offset.dot(along) / ds);
  state.frame.reference = state.anchor.reference + a * dx * Eigen::Vector3d::UnitX() + b * ds * along;
  if (const auto rail = track.rail_height(region.side, state.frame.reference.y())) {
    state.frame.reference.z() = rail->value;
  }
  // The lattice box the extent needs, with the guard elements of patch_grid.
  const Grid<double> needed = patch_grid(patch_extent(state.frame, region), dx, ds);
  const auto first_i = static_cast<Eigen::Index>(std::lround(needed.x0() / dx + a));
  const auto first_j = static_cast<Eigen::Index>(std::lround(needed.y0() / ds + b));
  const bool fits = kept && first_i >= kept->box_i && first_j >= kept->box_j &&
                    first_i + needed.mx() <= kept->box_i + kept->grid.mx() &&
                    first_j + needed.my() <= kept->box_j + kept->grid.my();
  Eigen::Index mx = needed.mx(), my = needed.my();
  if (fits) {
    state.box_i = kept->box_i, state.box_j = kept->box_j;
    mx = kept->grid.mx(), my = kept->grid.my();
  } else {  // a new box, with room to move before the next and a size from a coarse set
    auto rounded = [](Eigen::Index count) { return (count + 2 * box_margin + box_quantum - 1) / box_quantum * box_quantum; };
    mx = rounded(needed.mx()), my = rounded(needed.my());
    state.box_i = first_i - (mx - needed.mx()) / 2, state.box_j = first_j - (my - needed.my()) / 2;
  }
  state.grid = Grid<double>(mx, my, dx, ds, (static_cast<double>(state.box_i) - a) * dx,
                            (static_cast<double>(state.box_j) - b) * ds);
}

/// Whether a patch's grid numbers its elements as its only predecessor's did.
template <typename State>
bool same_box(const State& state, const std::vector<std::size_t>& predecessors, const std::vector<State>& previous) {
  if (predecessors.size() != 1) return false;
  const State& from = previous[predecessors.front()];
  return from.box_i == state.box_i && from.box_j == state.box_j && from.grid.mx() == state.grid.mx() &&
         from.grid.my() == state.grid.my();
}

/// The predecessors' contact sets mapped element by element onto the grid of `state`
/// (elements dx × ds, m; a pure shift on the lattice), sorted, without repeats, into `set`.
template <typename State>
void shifted_contact_set(const std::vector<std::size_t>& predecessors, const std::vector<State>& previous,
                         const State& state, double dx, double ds, std::vector<Eigen::Index>& set) {
  set.clear();
  const Eigen::Vector3d lateral = state.frame.lateral_axis();
  for (std::size_t p : predecessors) {
    const State& from = previous[p];
    const Eigen::Vector3d from_lateral = from.frame.lateral_axis();
    for (Eigen::Index k : from.contact_set) {
      const Eigen::Vector3d point = from.frame.reference + from.grid.x_of(k) * Eigen::Vector3d::UnitX() +
                                    from.grid.y_of(k) * from_lateral - state.frame.reference;
      const auto i = static_cast<Eigen::Index>(std::lround((point.x() - state.grid.x0()) / dx));
      const auto j = static_cast<Eigen::Index>(std::lround((point.dot(lateral) - state.grid.y0()) / ds));
      if (i >= 0 && i < state.grid.mx() && j >= 0 && j < state.grid.my()) set.push_back(state.grid.index(i, j));
    }
  }
  std::sort(set.begin(), set.end());
  set.erase(std::unique(set.begin(), set.end()), set.end());
}

}  // namespace fastnorm::wheelrail::detail
