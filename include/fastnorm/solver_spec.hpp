#pragma once
/// @file solver_spec.hpp
/// Which solver, with which settings, as a value: what tools, studies and the wheel–rail
/// layer pass around instead of a solver name (docs/architecture.md §3). The name grammar
/// lives here and nowhere else:
///
///     norm | cg | elliptic | polynomial[:G] | elliptic-edge[:K] | polynomial-edge[:G[:K]]
///
/// G is the polynomial grade (default 4), K the free edge elements at each end of a segment
/// (default 1). This header does not include the solvers; any_solver.hpp builds one.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <iterator>
#include <utility>
#include <string>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/solver_options.hpp"

namespace fastnorm {

/// A solver and its settings. Default: NORM with default options.
///
/// **Example**
/// @code
/// auto spec = fastnorm::SolverSpec<>::parse("polynomial-edge:4:1");
/// spec.active_set.max_iterations = 50;
/// fastnorm::AnySolver<> solver(spec, grid, steel);   // any_solver.hpp
/// @endcode
template <typename Scalar = double>
struct SolverSpec {
  enum class Kind { norm, cg, elliptic, polynomial, elliptic_edge, polynomial_edge };

  /// The names parse() accepts.
  static constexpr const char* grammar =
      "norm | cg | elliptic | polynomial[:G] | elliptic-edge[:K] | polynomial-edge[:G[:K]]";

  Kind kind = Kind::norm;
  int grade = 4;                         ///< G of the polynomial kinds, 0 to 30
  Eigen::Index edge_elements = 1;        ///< K of the edge-enriched kinds, ≥ 1
  ActiveSetOptions<Scalar> active_set;   ///< NORM and the reduced kinds
  CgOptions<Scalar> cg;                  ///< CG
  /// The reduced kinds' segment-table memory (bytes; ReducedOptions::table_budget_bytes).
  std::size_t table_budget_bytes = ReducedOptions<Scalar>().table_budget_bytes;

  /// The spec of a name of the grammar above, with default options.
  /// @throws fastnorm::invalid_argument for an unknown name or a bad G or K
  static SolverSpec parse(const std::string& text) {
    std::vector<std::string> parts(1);
    for (char c : text) {
      if (c == ':') parts.emplace_back(); else parts.back() += c;
    }
    const std::pair<const char*, Kind> kinds[] = {
        {"norm", Kind::norm},         {"cg", Kind::cg},
        {"elliptic", Kind::elliptic}, {"polynomial", Kind::polynomial},
        {"elliptic-edge", Kind::elliptic_edge}, {"polynomial-edge", Kind::polynomial_edge}};
    const auto* found = std::find_if(std::begin(kinds), std::end(kinds),
                                     [&](const auto& entry) { return parts[0] == entry.first; });
    FASTNORM_CHECK(found != std::end(kinds), "unknown solver '" + text + "' (known: " + grammar + ")");
    SolverSpec spec;
    spec.kind = found->second;
    // The ':' fields of each kind, in order: G, then K.
    const bool takes_grade = spec.kind == Kind::polynomial || spec.kind == Kind::polynomial_edge;
    const bool takes_edge = spec.kind == Kind::elliptic_edge || spec.kind == Kind::polynomial_edge;
    FASTNORM_CHECK(parts.size() <= std::size_t{1} + takes_grade + takes_edge,
                   "solver '" + text + "': too many ':' fields");
    std::size_t next = 1;
    if (takes_grade && next < parts.size()) spec.grade = whole_number(text, parts[next++], "the grade G");
    if (takes_edge && next < parts.size()) spec.edge_elements = whole_number(text, parts[next++], "the edge elements K");
    spec.validate();
    return spec;
  }

  /// The canonical name, defaults filled in: "polynomial:4", "polynomial-edge:4:1", …
  std::string name() const {
    const std::string g = std::to_string(grade), k = std::to_string(edge_elements);
    switch (kind) {
      case Kind::norm: return "norm";
      case Kind::cg: return "cg";
      case Kind::elliptic: return "elliptic";
      case Kind::polynomial: return "polynomial:" + g;
      case Kind::elliptic_edge: return "elliptic-edge:" + k;
      case Kind::polynomial_edge: return "polynomial-edge:" + g + ":" + k;
    }
    return "unknown";
  }

  /// The iteration cap of whichever kind the spec names: active-set solves (NORM and the
  /// reduced kinds) or CG iterations.
  void set_max_iterations(int count) { active_set.max_iterations = cg.max_iterations = count; }

  /// CG's stopping tolerance, `cg.tolerance` (CgOptions). The bindings set tolerances
  /// through these two, so that a tolerance given for a kind it does not apply to is
  /// refused, not ignored; a refused value leaves the spec as it was.
  /// @throws fastnorm::invalid_argument for a spec that is not CG, or a bad value
  void set_cg_tolerance(Scalar tolerance) {
    FASTNORM_CHECK(kind == Kind::cg, "solver spec: tolerance is the CG solver's stopping tolerance; '" + name() +
                                         "' is an active-set solver, whose join tolerance is gap_tolerance");
    CgOptions<Scalar> checked = cg;
    checked.tolerance = tolerance;
    checked.validate();
    cg = checked;
  }

  /// The join check's τ of NORM and the reduced kinds, `active_set.gap_tolerance`
  /// (ActiveSetOptions; relative to max|h|).
  /// @throws fastnorm::invalid_argument for CG, or a bad value
  void set_gap_tolerance(Scalar tolerance) {
    FASTNORM_CHECK(kind != Kind::cg, "solver spec: gap_tolerance is the join tolerance of the active-set solvers; "
                                     "'cg' stops by its tolerance");
    ActiveSetOptions<Scalar> checked = active_set;
    checked.gap_tolerance = tolerance;
    checked.validate();
    active_set = checked;
  }

  /// One of the reduced strip-basis kinds.
  bool is_reduced() const { return kind != Kind::norm && kind != Kind::cg; }

  /// The options of a reduced solver of this spec.
  ReducedOptions<Scalar> reduced_options() const { return {active_set, table_budget_bytes}; }

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    FASTNORM_CHECK(grade >= 0 && grade <= 30, detail::describe("solver spec: the grade must lie in [0, 30]", grade));
    FASTNORM_CHECK(edge_elements >= 1, detail::describe("solver spec: edge_elements must be >= 1", edge_elements));
    active_set.validate();
    cg.validate();
  }

 private:
  static int whole_number(const std::string& text, const std::string& field, const char* what) {
    const bool digits = !field.empty() && field.size() <= 9 &&
                        field.find_first_not_of("0123456789") == std::string::npos;
    FASTNORM_CHECK(digits, "solver '" + text + "': " + what + " must be a whole number, not '" + field + "'");
    return std::stoi(field);
  }
};

}  // namespace fastnorm
