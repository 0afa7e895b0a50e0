#pragma once
/// @file contact_table.hpp
/// A contact table looked up in a vehicle-dynamics time loop (docs/tables.md §4): results
/// precomputed on a grid of (lateral shift y, yaw, load) for one or more wheel/rail profile
/// pairs, interpolated multilinearly or by monotone cubics (PCHIP), with a topology guard:
/// a query whose cell's corners differ in topology (patch count, status) is answered
/// `topology_change`, never a blend, so that the caller evaluates the contact directly.
///
/// The table is built from arrays (`ContactTable`'s constructor) or read from the small
/// binary file that `fastnorm-table export` writes (`read_contact_table`); no HDF5 here.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "fastnorm/error.hpp"

namespace fastnorm {

/// How ContactTable::lookup interpolates between the nodes of a cell.
enum class TableInterpolation {
  multilinear,  ///< the product of linear interpolations: continuous, exact for multilinear data
  pchip,  ///< Fritsch–Carlson monotone cubics, one axis after the other (docs/tables.md §4): C¹ along each
          ///< axis, no overshoot of monotone data, exact for linear data
};

/// What a lookup found.
enum class TableLookupStatus {
  ok,               ///< the outputs are written
  out_of_range,     ///< a coordinate lies outside its axis (or is NaN); nothing written
  topology_change,  ///< the cell's corners differ in topology; nothing written: evaluate directly
  failed_case,      ///< the cell's corners agree but hold failed cases; nothing written
};

inline const char* to_string(TableLookupStatus status) {
  switch (status) {
    case TableLookupStatus::ok: return "ok";
    case TableLookupStatus::out_of_range: return "out of range";
    case TableLookupStatus::topology_change: return "topology change";
    case TableLookupStatus::failed_case: return "failed case";
  }
  return "unknown";
}

/// The nodes of a table, shared by all its pairs; each axis strictly increasing. An axis of
/// one node is fixed: a lookup must give that value (to 1e-12 relative).
struct TableAxes {
  std::vector<double> lateral_shift_m;  ///< y, the wheelset's lateral shift (m)
  std::vector<double> yaw_rad;          ///< the wheelset's yaw angle (rad)
  std::vector<double> load_n;           ///< the vertical load on the wheelset (N)
};

/// A table of named outputs over (pair, load, yaw, y). Layout of `values`: pair slowest, then
/// load, yaw, y, and the outputs of one case contiguous (fastest). `topology`: one code per
/// case (same order without the outputs), ≥ 0 for a solved case (cases interpolate together
/// only when their codes are equal, e.g. the patch counts of both wheels), < 0 for a failed
/// one (its values are not read).
class ContactTable {
 public:
  static constexpr std::size_t axis_count = 3;

  /// `measured_shift_derivatives`: empty, or dv/dy of every case and output in the layout of
  /// `values` (the output's unit per metre), measured when the table was built, e.g. by the
  /// central differences of equilibria at y ± Δ (docs/tables.md §4); NaN where none was
  /// measured. A finite one replaces PCHIP's estimate at its node along y, limited so that
  /// monotone data stay monotone: zero where the secants to the neighbours of the same code
  /// differ in sign from each other or from it, else at most three times the smaller secant
  /// (Fritsch and Carlson's sufficient condition).
  /// @throws fastnorm::invalid_argument naming the argument: an empty or non-increasing axis,
  /// non-finite nodes, names and units of different lengths, sizes that do not match, a
  /// non-finite value of a solved case, an infinite measured derivative
  ContactTable(TableAxes axes, std::vector<std::string> pair_names, std::vector<std::string> output_names,
               std::vector<std::string> output_units, std::vector<double> values, std::vector<std::int32_t> topology,
               std::vector<double> measured_shift_derivatives = {})
      : axes_(std::move(axes)),
        pair_names_(std::move(pair_names)),
        output_names_(std::move(output_names)),
        output_units_(std::move(output_units)),
        values_(std::move(values)),
        topology_(std::move(topology)),
        measured_shift_derivatives_(std::move(measured_shift_derivatives)) {
    check_axis(axes_.lateral_shift_m, "axes.lateral_shift_m");
    check_axis(axes_.yaw_rad, "axes.yaw_rad");
    check_axis(axes_.load_n, "axes.load_n");
    FASTNORM_CHECK(!pair_names_.empty(), "pair_names must name at least one profile pair");
    FASTNORM_CHECK(!output_names_.empty(), "output_names must name at least one output");
    FASTNORM_CHECK(output_units_.size() == output_names_.size(),
                   describe("output_units must give one unit per output (" + std::to_string(output_names_.size()) +
                                " outputs)",
                            output_units_.size()));
    const std::size_t cases = pair_names_.size() * cases_per_pair();
    FASTNORM_CHECK(topology_.size() == cases,
                   describe("topology must hold one code per case (pairs × loads × yaws × shifts = " +
                                std::to_string(cases) + ")",
                            topology_.size()));
    FASTNORM_CHECK(values_.size() == cases * outputs(),
                   describe("values must hold outputs × cases = " + std::to_string(cases * outputs()) + " numbers",
                            values_.size()));
    for (std::size_t c = 0; c < cases; ++c) {
      if (topology_[c] < 0) continue;
      for (std::size_t o = 0; o < outputs(); ++o)
        FASTNORM_CHECK(std::isfinite(values_[c * outputs() + o]),
                       describe("values: output '" + output_names_[o] + "' of solved case " + std::to_string(c) +
                                    " must be finite",
                                values_[c * outputs() + o]));
    }
    FASTNORM_CHECK(measured_shift_derivatives_.empty() || measured_shift_derivatives_.size() == values_.size(),
                   describe("measured_shift_derivatives must be empty or hold one number per value (" +
                                std::to_string(values_.size()) + ")",
                            measured_shift_derivatives_.size()));
    for (std::size_t k = 0; k < measured_shift_derivatives_.size(); ++k)
      FASTNORM_CHECK(!std::isinf(measured_shift_derivatives_[k]),
                     describe("measured_shift_derivatives[" + std::to_string(k) + "] must be finite or NaN",
                              measured_shift_derivatives_[k]));
    differentiate_along_y();
  }

  const TableAxes& axes() const { return axes_; }
  const std::vector<std::string>& pair_names() const { return pair_names_; }
  const std::vector<std::string>& output_names() const { return output_names_; }
  const std::vector<std::string>& output_units() const { return output_units_; }
  const std::vector<double>& values() const { return values_; }
  const std::vector<std::int32_t>& topology() const { return topology_; }
  /// As given to the constructor (empty: none).
  const std::vector<double>& measured_shift_derivatives() const { return measured_shift_derivatives_; }
  std::size_t pairs() const { return pair_names_.size(); }
  std::size_t outputs() const { return output_names_.size(); }

  /// The position of the output called `name`.
  /// @throws fastnorm::invalid_argument if there is none
  std::size_t output_index(const std::string& name) const {
    const auto found = std::find(output_names_.begin(), output_names_.end(), name);
    FASTNORM_CHECK(found != output_names_.end(), "no output named '" + name + "' in the table");
    return static_cast<std::size_t>(found - output_names_.begin());
  }

  /// The outputs at (y, yaw, load) for `pair`, written to out[0 .. outputs()) when the status
  /// is ok; out is not touched otherwise. Allocation-free.
  /// @throws fastnorm::invalid_argument if pair is not a pair of the table
  TableLookupStatus lookup(std::size_t pair, double lateral_shift_m, double yaw_rad, double load_n,
                           TableInterpolation interpolation, double* out) const {
    FASTNORM_CHECK(pair < pairs(), describe("pair must be below the table's " + std::to_string(pairs()) + " pairs", pair));
    Located located{{lateral_shift_m, yaw_rad, load_n}, {}, pair * cases_per_pair()};
    for (std::size_t a = 0; a < axis_count; ++a)
      if (!locate(axis_nodes(a), located.query[a], located.cell[a])) return TableLookupStatus::out_of_range;

    const std::int32_t code = topology_[case_at(located, located.cell)];
    // The guard: every corner of the cell has the same code.
    for (std::size_t corner = 1; corner < (std::size_t{1} << axis_count); ++corner) {
      NodeIndex at = located.cell;
      bool exists = true;
      for (std::size_t a = 0; a < axis_count; ++a)
        if (corner >> a & 1) exists = exists && (at[a] += 1) < axis_nodes(a).size();
      if (exists && topology_[case_at(located, at)] != code) return TableLookupStatus::topology_change;
    }
    if (code < 0) return TableLookupStatus::failed_case;

    if (interpolation == TableInterpolation::multilinear)
      interpolate_multilinear(located, out);
    else
      interpolate_pchip(located, code, out);
    return TableLookupStatus::ok;
  }

 private:
  /// A node per axis: 0 = y (fastest in memory), 1 = yaw, 2 = load.
  using NodeIndex = std::array<std::size_t, axis_count>;

  /// A query placed in the table: its coordinates, its cell's lower node on each axis, and
  /// the first case of its pair.
  struct Located {
    std::array<double, axis_count> query;
    NodeIndex cell;
    std::size_t first_case;
  };

  const std::vector<double>& axis_nodes(std::size_t a) const {
    return a == 0 ? axes_.lateral_shift_m : a == 1 ? axes_.yaw_rad : axes_.load_n;
  }

  std::size_t cases_per_pair() const {
    return axes_.lateral_shift_m.size() * axes_.yaw_rad.size() * axes_.load_n.size();
  }

  /// The case at node `at` of the located query's pair.
  std::size_t case_at(const Located& located, const NodeIndex& at) const {
    return located.first_case + at[0] + axes_.lateral_shift_m.size() * (at[1] + axes_.yaw_rad.size() * at[2]);
  }

  static void check_axis(const std::vector<double>& axis, const std::string& name) {
    FASTNORM_CHECK(!axis.empty(), name + " must hold at least one node");
    for (std::size_t i = 0; i < axis.size(); ++i) {
      FASTNORM_CHECK(std::isfinite(axis[i]), describe(name + "[" + std::to_string(i) + "] must be finite", axis[i]));
      if (i > 0)
        FASTNORM_CHECK(axis[i] > axis[i - 1],
                       describe(name + " must increase strictly: " + name + "[" + std::to_string(i) + "]", axis[i]));
    }
  }

  /// The cell [nodes[cell], nodes[cell + 1]] holding x (cell = the last interval at the
  /// upper end); on a one-node axis, cell 0 if x is that node. False outside (or NaN).
  static bool locate(const std::vector<double>& nodes, double x, std::size_t& cell) {
    if (nodes.size() == 1) {
      cell = 0;
      return std::abs(x - nodes[0]) <= 1e-12 * std::max(1.0, std::abs(nodes[0]));
    }
    if (!(x >= nodes.front() && x <= nodes.back())) return false;
    const auto above = std::upper_bound(nodes.begin() + 1, nodes.end() - 1, x);
    cell = static_cast<std::size_t>(above - nodes.begin()) - 1;
    return true;
  }

  /// The fraction of the way across the cell (0 on a one-node axis).
  static double fraction(const std::vector<double>& nodes, std::size_t cell, double x) {
    return nodes.size() == 1 ? 0.0 : (x - nodes[cell]) / (nodes[cell + 1] - nodes[cell]);
  }

  void interpolate_multilinear(const Located& located, double* out) const {
    std::array<double, axis_count> t{};
    for (std::size_t a = 0; a < axis_count; ++a)
      t[a] = fraction(axis_nodes(a), located.cell[a], located.query[a]);
    const std::size_t n = outputs();
    std::fill(out, out + n, 0.0);
    for (std::size_t corner = 0; corner < (std::size_t{1} << axis_count); ++corner) {
      double weight = 1;
      NodeIndex at = located.cell;
      for (std::size_t a = 0; a < axis_count; ++a) {
        const bool upper = corner >> a & 1;
        weight *= upper ? t[a] : 1 - t[a];
        at[a] += upper;
      }
      if (weight == 0) continue;  // also skips the missing upper node of a one-node axis
      const double* corner_values = values_.data() + case_at(located, at) * n;
      for (std::size_t o = 0; o < n; ++o) out[o] += weight * corner_values[o];
    }
  }

  /// The stencil of axis a: nodes [first, last] around the cell, at most one node beyond each
  /// side, within the axis.
  struct Stencil {
    std::size_t first = 0, last = 0;
  };

  /// PCHIP, one axis after the other (docs/tables.md §4). Along y, the derivatives at the
  /// cell's nodes were computed when the table was built (differentiate_along_y), each from
  /// its own line's neighbours of its own code. Along yaw and load, the stencil of up to
  /// 4 × 4 cases around the cell gives them; an outer layer of it (one side of one axis)
  /// holding a case of another topology is dropped, so that the derivatives at the cell's
  /// nodes become one-sided there. Nothing across a topology change enters.
  void interpolate_pchip(const Located& located, std::int32_t code, double* out) const {
    const NodeIndex& cell = located.cell;
    std::array<Stencil, axis_count> full{};
    for (std::size_t a = 0; a < axis_count; ++a) {
      const std::size_t size = axis_nodes(a).size();
      full[a].first = cell[a] > 0 ? cell[a] - 1 : 0;
      full[a].last = size == 1 ? 0 : std::min(cell[a] + 2, size - 1);
    }
    std::array<Stencil, axis_count> kept = full;
    for (std::size_t a = 1; a < axis_count; ++a) {
      if (full[a].first < cell[a] && !layer_matches(located, full, a, full[a].first, code)) kept[a].first = cell[a];
      const std::size_t upper = std::min(cell[a] + 1, full[a].last);
      if (full[a].last > upper && !layer_matches(located, full, a, full[a].last, code)) kept[a].last = upper;
    }
    const CellWeights along_shift(axis_nodes(0), cell[0], located.query[0]);
    const std::array<PchipAxis, 2> axis{PchipAxis(axis_nodes(1), kept[1], cell[1], located.query[1]),
                                        PchipAxis(axis_nodes(2), kept[2], cell[2], located.query[2])};

    // Values along y for every (yaw, load) line of the stencil, then along yaw, then load.
    const std::size_t n = outputs();
    for (std::size_t o = 0; o < n; ++o) {
      std::array<double, 4> along_yaw{};
      std::array<double, 4> along_load{};
      for (std::size_t k = 0; k < axis[1].stencil.count; ++k) {
        for (std::size_t j = 0; j < axis[0].stencil.count; ++j) {
          const std::size_t at =
              case_at(located, {cell[0], axis[0].stencil.first + j, axis[1].stencil.first + k}) * n + o;
          along_yaw[j] = along_shift.hermite(values_.data() + at, shift_derivatives_.data() + at, n);
        }
        along_load[k] = axis[0].evaluate(along_yaw);
      }
      out[o] = axis[1].evaluate(along_load);
    }
  }

  /// Whether every case of the stencil `box` whose index along axis a is `index` has `code`.
  bool layer_matches(const Located& located, const std::array<Stencil, axis_count>& box, std::size_t a,
                     std::size_t index, std::int32_t code) const {
    std::array<Stencil, axis_count> layer = box;
    layer[a] = {index, index};
    for (std::size_t k = layer[2].first; k <= layer[2].last; ++k)
      for (std::size_t j = layer[1].first; j <= layer[1].last; ++j)
        for (std::size_t i = layer[0].first; i <= layer[0].last; ++i)
          if (topology_[case_at(located, {i, j, k})] != code) return false;
    return true;
  }

  /// The derivative along y of every solved case and output, in the layout of values_:
  /// PCHIP's from the nodes of its own line (yaw, load and pair fixed) within one of it on
  /// each side that have its code, and two on one side where the other is missing (the
  /// one-sided estimate); or the measured one, limited (see the constructor). Done once, so
  /// that a lookup's 16 lines along y are each a cubic Hermite form of two values and two
  /// derivatives (docs/tables.md §4).
  void differentiate_along_y() {
    const std::vector<double>& nodes = axes_.lateral_shift_m;
    const std::size_t shifts = nodes.size(), n = outputs();
    shift_derivatives_.assign(values_.size(), 0.0);
    if (shifts == 1) return;
    for (std::size_t line = 0; line < topology_.size(); line += shifts) {
      const std::int32_t* code = topology_.data() + line;
      auto same = [&](std::size_t i, std::size_t other) { return code[other] == code[i]; };
      for (std::size_t i = 0; i < shifts; ++i) {
        if (code[i] < 0) continue;
        const bool left = i > 0 && same(i, i - 1);
        const bool right = i + 1 < shifts && same(i, i + 1);
        if (!left && !right) continue;  // every cell it bounds is a topology change
        std::size_t first = left ? i - 1 : i;
        std::size_t last = right ? i + 1 : i;
        if (!left && last + 1 < shifts && same(i, last + 1)) ++last;  // one-sided from above
        if (!right && first > 0 && same(i, first - 1)) --first;       // one-sided from below
        const PchipStencil stencil(nodes, {first, last});
        const std::size_t node = i - first;  // within the stencil
        for (std::size_t o = 0; o < n; ++o) {
          const std::size_t at = (line + i) * n + o;
          std::array<double, 4> run{};
          for (std::size_t s = 0; s < stencil.count; ++s) run[s] = values_[(line + first + s) * n + o];
          const std::array<double, 3> slope = stencil.slopes(run);
          if (!measured_shift_derivatives_.empty() && !std::isnan(measured_shift_derivatives_[at])) {
            // The secants to the neighbours of its code: the one there is, twice, at an end.
            const double before = left ? slope[node - 1] : slope[node], after = right ? slope[node] : slope[node - 1];
            shift_derivatives_[at] = limited(measured_shift_derivatives_[at], before, after);
          } else {
            shift_derivatives_[at] = stencil.derivative(slope, node);
          }
        }
      }
    }
  }

  /// A measured derivative kept within Fritsch and Carlson's square: zero unless it and the
  /// secants before and after the node (the same one twice at an end) share a sign, else at
  /// most three times the smaller secant, so that the Hermite cubic of a monotone cell is
  /// monotone.
  static double limited(double derivative, double before, double after) {
    if (before * after <= 0 || derivative * before <= 0) return 0;
    const double bound = 3 * std::min(std::abs(before), std::abs(after));
    return std::abs(derivative) > bound ? std::copysign(bound, derivative) : derivative;
  }

  /// The nodes of a PCHIP stencil along one axis (2 to 4 of them) and what depends on them
  /// only: the inverse widths for the slopes and the derivative formulas' weights.
  struct PchipStencil {
    std::size_t first = 0;  ///< the stencil's first node on the axis
    std::size_t count = 1;  ///< its nodes (1: a one-node axis, no interpolation)
    std::array<double, 3> inverse_width{};
    /// Per node s of the stencil: inside, the Fritsch–Butland weights w1, w2 of the harmonic mean
    /// (w1 + w2) / (w1/m_s−1 + w2/m_s); at an end, the one-sided estimate's (2h0 + h1)/(h0 + h1)
    /// and h0/(h0 + h1).
    std::array<std::array<double, 2>, 4> derivative_weight{};

    PchipStencil() = default;
    PchipStencil(const std::vector<double>& nodes, const Stencil& stencil)
        : first(stencil.first), count(stencil.last - stencil.first + 1) {
      std::array<double, 3> width{};
      for (std::size_t s = 0; s + 1 < count; ++s) {
        width[s] = nodes[first + s + 1] - nodes[first + s];
        inverse_width[s] = 1 / width[s];
      }
      for (std::size_t s = 0; s < count; ++s) {
        if (s > 0 && s + 1 < count) {
          derivative_weight[s] = {2 * width[s] + width[s - 1], width[s] + 2 * width[s - 1]};
        } else if (count > 2) {
          const double h0 = width[s == 0 ? 0 : count - 2];
          const double h1 = width[s == 0 ? 1 : count - 3];
          derivative_weight[s] = {(2 * h0 + h1) / (h0 + h1), h0 / (h0 + h1)};
        }
      }
    }

    std::array<double, 3> slopes(const std::array<double, 4>& values) const {
      std::array<double, 3> slope{};
      for (std::size_t s = 0; s + 1 < count; ++s) slope[s] = (values[s + 1] - values[s]) * inverse_width[s];
      return slope;
    }

    /// The derivative PCHIP gives node s: inside, zero at a local extremum, else the weighted
    /// harmonic mean of the two slopes (Fritsch and Butland); at an end, the three-point
    /// one-sided estimate limited to keep the shape (zero if of the wrong sign, at most three
    /// times the slope), or the slope itself when the stencil is a single interval.
    double derivative(const std::array<double, 3>& slope, std::size_t s) const {
      if (count == 2) return slope[0];
      const auto& w = derivative_weight[s];
      if (s > 0 && s + 1 < count) {
        const double before = slope[s - 1];
        const double after = slope[s];
        if (before * after <= 0) return 0;
        return (w[0] + w[1]) * before * after / (w[0] * after + w[1] * before);
      }
      const double near = slope[s == 0 ? 0 : count - 2];
      const double far = slope[s == 0 ? 1 : count - 3];
      const double d = w[0] * near - w[1] * far;
      if (d * near <= 0) return 0;
      if (near * far <= 0 && std::abs(d) > 3 * std::abs(near)) return 3 * near;
      return d;
    }
  };

  /// The cubic Hermite form on a cell [x_c, x_c+1] at the query, about its lower value:
  /// p = v_c + lift (v_c+1 − v_c) + lower_weight d_c + upper_weight d_c+1.
  struct CellWeights {
    double lift = 0, lower_weight = 0, upper_weight = 0;
    bool interpolates = false;  ///< false on a one-node axis: the node's value
    bool at_upper_end = false;  ///< t = 1 at the axis's end: the upper node's value exactly

    CellWeights() = default;
    CellWeights(const std::vector<double>& nodes, std::size_t cell, double x) : interpolates(nodes.size() > 1) {
      if (!interpolates) return;
      const double h = nodes[cell + 1] - nodes[cell];
      const double t = (x - nodes[cell]) / h;
      at_upper_end = t == 1;
      lift = t * t * (3 - 2 * t);
      lower_weight = h * t * (t - 1) * (t - 1);
      upper_weight = h * t * t * (t - 1);
    }

    double hermite(double lower, double upper, double lower_derivative, double upper_derivative) const {
      if (!interpolates) return lower;
      if (at_upper_end) return upper;
      return lower + lift * (upper - lower) + lower_weight * lower_derivative + upper_weight * upper_derivative;
    }
    /// The same from the cell's lower node's value and derivative, the upper's `stride` further.
    double hermite(const double* value, const double* derivative, std::size_t stride) const {
      if (!interpolates) return value[0];
      return hermite(value[0], value[stride], derivative[0], derivative[stride]);
    }
  };

  /// PCHIP along yaw or load: the stencil kept around the cell and the cell's weights, set up
  /// once per lookup, then `evaluate` for each line of values along the axis.
  struct PchipAxis {
    PchipStencil stencil;
    std::size_t cell = 0;  ///< the cell's lower node within the stencil
    CellWeights weights;

    PchipAxis(const std::vector<double>& nodes, const Stencil& kept, std::size_t cell_on_axis, double x)
        : stencil(nodes, kept), cell(cell_on_axis - kept.first), weights(nodes, cell_on_axis, x) {}

    double evaluate(const std::array<double, 4>& values) const {
      if (stencil.count == 1) return values[0];
      const std::array<double, 3> slope = stencil.slopes(values);
      return weights.hermite(values[cell], values[cell + 1], stencil.derivative(slope, cell),
                             stencil.derivative(slope, cell + 1));
    }
  };

  TableAxes axes_;
  std::vector<std::string> pair_names_;
  std::vector<std::string> output_names_;
  std::vector<std::string> output_units_;
  std::vector<double> values_;
  std::vector<std::int32_t> topology_;
  std::vector<double> measured_shift_derivatives_;  // as given: empty, or values_' layout with NaN where none
  std::vector<double> shift_derivatives_;  // dv/dy at every case and output (values_' layout), PCHIP's or measured
};

}  // namespace fastnorm
