#pragma once
/// @file any_solver.hpp
/// A solver chosen at run time by a SolverSpec (or its name, solver_spec.hpp): for tools,
/// studies and the wheel–rail layer. Including this header instantiates nothing; using
/// AnySolver instantiates every solver, so code that needs one solver only should name it.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <utility>

#include "fastnorm/bases.hpp"
#include "fastnorm/cg_solver.hpp"
#include "fastnorm/detail/solver_base.hpp"
#include "fastnorm/norm_solver.hpp"
#include "fastnorm/reduced_solver.hpp"
#include "fastnorm/solver_from_spec.hpp"
#include "fastnorm/solver_spec.hpp"
#include "fastnorm/warm_start.hpp"

namespace fastnorm {

template <typename Scalar>
class AnySolver;

/// The workspace of an AnySolver: holds the workspace of the solver it was last used with
/// (created on first use; replaced, keeping its start, when used with a solver of another
/// kind).
template <typename Scalar = double>
class AnyWorkspace {
 public:
  AnyWorkspace() = default;
  AnyWorkspace(const AnyWorkspace& other) : model_(other.model_ ? other.model_->clone() : nullptr), pending_(other.pending_) {}
  /// Copied into the held workspace when both hold one of the same type, so that its
  /// storage serves again (a time loop's trial steps: WheelsetContact::restore).
  AnyWorkspace& operator=(const AnyWorkspace& other) {
    if (this == &other) return *this;
    if (model_ && other.model_ && model_->assign(*other.model_)) {
      pending_ = other.pending_;
    } else {
      *this = AnyWorkspace(other);
    }
    return *this;
  }
  AnyWorkspace(AnyWorkspace&&) noexcept = default;
  AnyWorkspace& operator=(AnyWorkspace&&) noexcept = default;
  ~AnyWorkspace() = default;

  /// Where the next solve starts (see the workspace of each solver).
  WarmStart<Scalar>& start() { return model_ ? model_->start() : pending_; }
  const WarmStart<Scalar>& start() const { return model_ ? model_->start() : pending_; }
  /// The next solve is cold (storage kept).
  void forget() {
    if (model_) model_->forget();
    pending_.clear();
  }
  /// Storage for the next solve's answer (see the workspace of each solver); dropped before
  /// the first solve.
  void recycle(Solution<Scalar>&& used) {
    if (model_) model_->recycle(std::move(used));
  }

 private:
  template <typename>
  friend class AnySolver;

  struct Model {
    virtual ~Model() = default;
    virtual WarmStart<Scalar>& start() = 0;
    virtual void forget() = 0;
    virtual void recycle(Solution<Scalar>&& used) = 0;
    virtual std::unique_ptr<Model> clone() const = 0;
    /// Copies `other` into this one if it holds the same type; false otherwise.
    virtual bool assign(const Model& other) = 0;
  };
  template <typename Workspace>
  struct Holder final : Model {
    WarmStart<Scalar>& start() override { return workspace.start(); }
    void forget() override { workspace.forget(); }
    void recycle(Solution<Scalar>&& used) override { workspace.recycle(std::move(used)); }
    std::unique_ptr<Model> clone() const override { return std::make_unique<Holder>(*this); }
    bool assign(const Model& other) override {
      const auto* same = dynamic_cast<const Holder*>(&other);
      if (same) workspace = same->workspace;
      return same != nullptr;
    }
    Workspace workspace;
  };

  /// The held workspace as a `Workspace`, replaced by a new one (with the same start) if it
  /// is of another type.
  template <typename Workspace>
  Workspace& as() {
    if (auto* held = dynamic_cast<Holder<Workspace>*>(model_.get())) return held->workspace;
    auto fresh = std::make_unique<Holder<Workspace>>();
    fresh->workspace.start() = std::move(start());
    model_ = std::move(fresh);
    pending_.clear();
    return static_cast<Holder<Workspace>&>(*model_).workspace;
  }

  std::unique_ptr<Model> model_;
  WarmStart<Scalar> pending_;  // the start set before the first solve
};

/// Any of fastnorm's solvers behind one interface (the solver concept of
/// docs/architecture.md §2). A copy is a separate solver with its own sequence workspace.
template <typename Scalar = double>
class AnySolver : public detail::SolverBase<AnySolver<Scalar>, AnyWorkspace<Scalar>, Scalar> {
  using Base = detail::SolverBase<AnySolver<Scalar>, AnyWorkspace<Scalar>, Scalar>;

 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Workspace = AnyWorkspace<Scalar>;
  using Base::solve;

  /// @throws fastnorm::invalid_argument for an invalid spec
  AnySolver(const SolverSpec<Scalar>& spec, const Grid<Scalar>& grid, const Material<Scalar>& material);

  /// By name, with default options.
  /// @throws fastnorm::invalid_argument for an unknown name or bad G, K
  AnySolver(const std::string& name, const Grid<Scalar>& grid, const Material<Scalar>& material)
      : AnySolver(SolverSpec<Scalar>::parse(name), grid, material) {}

  AnySolver(const AnySolver& other)
      : Base(other), spec_(other.spec_), material_(other.material_), model_(other.model_->clone()) {}
  AnySolver& operator=(const AnySolver& other) {
    if (this != &other) *this = AnySolver(other);
    return *this;
  }
  AnySolver(AnySolver&&) noexcept = default;
  AnySolver& operator=(AnySolver&&) noexcept = default;
  ~AnySolver() = default;

  /// The canonical name, with defaults filled in (e.g. "polynomial:4").
  std::string name() const { return spec_.name(); }
  const SolverSpec<Scalar>& spec() const { return spec_; }
  const Grid<Scalar>& grid() const { return model_->grid(); }

  /// A solver of this one's spec and material on `grid`: for a reduced kind,
  /// ReducedSolver::for_grid (sharing the segment tables where they reach), else a new one.
  AnySolver for_grid(const Grid<Scalar>& grid) const {
    return AnySolver(spec_, material_, model_->for_grid(grid, spec_, material_));
  }

  /// For a reduced kind, ReducedSolver::build_tables; else false (nothing to build).
  bool build_tables() const { return model_->build_tables(); }

  /// The chosen solver's solve(h, loading, workspace).
  Solution<Scalar> solve(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading,
                         Workspace& workspace) const {
    return model_->solve(undeformed_distance, loading, workspace);
  }

  /// The chosen solver's normal_stiffness: dFn/dδ (N/m) at the contact set of `solution`,
  /// the last solve in `workspace`.
  Scalar normal_stiffness(const Solution<Scalar>& solution, Workspace& workspace) const {
    return model_->normal_stiffness(solution, workspace);
  }

 private:
  struct Model {
    virtual ~Model() = default;
    virtual Solution<Scalar> solve(const Eigen::Ref<const Vector>& h, const Loading<Scalar>& loading,
                                   Workspace& workspace) const = 0;
    virtual Scalar normal_stiffness(const Solution<Scalar>& solution, Workspace& workspace) const = 0;
    virtual const Grid<Scalar>& grid() const = 0;
    virtual std::unique_ptr<Model> clone() const = 0;
    virtual std::unique_ptr<Model> for_grid(const Grid<Scalar>& grid, const SolverSpec<Scalar>& spec,
                                            const Material<Scalar>& material) const = 0;
    virtual bool build_tables() const = 0;
  };

  template <typename Solver>
  struct Holder final : Model {
    explicit Holder(Solver held) : solver(std::move(held)) {}
    Solution<Scalar> solve(const Eigen::Ref<const Vector>& h, const Loading<Scalar>& loading,
                           Workspace& workspace) const override {
      return solver.solve(h, loading, workspace.template as<typename Solver::Workspace>());
    }
    Scalar normal_stiffness(const Solution<Scalar>& solution, Workspace& workspace) const override {
      return solver.normal_stiffness(solution, workspace.template as<typename Solver::Workspace>());
    }
    const Grid<Scalar>& grid() const override { return solver.grid(); }
    std::unique_ptr<Model> clone() const override { return std::make_unique<Holder>(solver); }
    std::unique_ptr<Model> for_grid(const Grid<Scalar>& grid, const SolverSpec<Scalar>& spec,
                                    const Material<Scalar>& material) const override {
      if constexpr (detail::shares_tables<Solver>) {
        return std::make_unique<Holder>(solver.for_grid(grid));
      } else {
        return std::make_unique<Holder>(SolverFromSpec<Solver>::make(spec, grid, material));
      }
    }
    bool build_tables() const override {
      if constexpr (detail::shares_tables<Solver>) {
        return solver.build_tables();
      } else {
        return false;
      }
    }
    Solver solver;
  };

  AnySolver(const SolverSpec<Scalar>& spec, const Material<Scalar>& material, std::unique_ptr<Model> model)
      : spec_(spec), material_(material), model_(std::move(model)) {}

  template <typename Solver>
  void adopt(const Grid<Scalar>& grid, const Material<Scalar>& material) {
    model_ = std::make_unique<Holder<Solver>>(SolverFromSpec<Solver>::make(spec_, grid, material));
  }

  SolverSpec<Scalar> spec_;
  Material<Scalar> material_;
  std::unique_ptr<Model> model_;
};

// Defined out of the class, so not inline: with the explicit instantiation declaration
// below, a program linked with fastnorm::precompiled does not compile every solver again.
template <typename Scalar>
AnySolver<Scalar>::AnySolver(const SolverSpec<Scalar>& spec, const Grid<Scalar>& grid, const Material<Scalar>& material)
    : spec_(spec), material_(material) {
  spec_.validate();
  using Kind = typename SolverSpec<Scalar>::Kind;
  switch (spec_.kind) {
    case Kind::norm: adopt<NormSolver<Scalar>>(grid, material); break;
    case Kind::cg: adopt<CgSolver<Scalar>>(grid, material); break;
    case Kind::elliptic: adopt<ReducedSolver<EllipticBasis, Scalar>>(grid, material); break;
    case Kind::polynomial: adopt<ReducedSolver<PolynomialBasis, Scalar>>(grid, material); break;
    case Kind::elliptic_edge: adopt<ReducedSolver<EllipticEdgeBasis, Scalar>>(grid, material); break;
    case Kind::polynomial_edge: adopt<ReducedSolver<PolynomialEdgeBasis, Scalar>>(grid, material); break;
  }
}

#ifdef FASTNORM_PRECOMPILED
// fastnorm::precompiled (CMakeLists.txt) holds AnySolver<double> compiled once, and sets
// this macro for the programs that link it (docs/contributing.md, compile cost).
extern template class AnySolver<double>;
#endif

/// AnySolver solves every kind of spec.
template <typename Scalar>
struct SolverFromSpec<AnySolver<Scalar>> {
  static bool accepts(typename SolverSpec<Scalar>::Kind) { return true; }
  static AnySolver<Scalar> make(const SolverSpec<Scalar>& spec, const Grid<Scalar>& grid,
                                const Material<Scalar>& material) {
    return AnySolver<Scalar>(spec, grid, material);
  }
};

}  // namespace fastnorm
