#pragma once
/// @file any_solver.hpp
/// A solver chosen at run time by name (for tools and studies that compare solvers):
///   norm | cg | elliptic | polynomial[:G] | elliptic-edge[:K] | polynomial-edge[:G[:K]]
/// G is the polynomial grade (default 4), K the free edge elements per segment end
/// (default 1).

#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "fastnorm/bases.hpp"
#include "fastnorm/cg_solver.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/norm_solver.hpp"
#include "fastnorm/reduced_solver.hpp"

namespace fastnorm {

/// Any of fastnorm's solvers behind one interface. A copy is a separate solver with its own
/// memory of the sequence (see solve_next).
template <typename Scalar = double>
class AnySolver {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// @param name see the file comment
  /// @throws fastnorm::invalid_argument for an unknown name or bad G, K
  AnySolver(const std::string& name, const Grid<Scalar>& grid, const Material<Scalar>& material,
            ActiveSetOptions<Scalar> options = {}) {
    std::vector<std::string> parts;
    std::istringstream split(name);
    for (std::string part; std::getline(split, part, ':');) parts.push_back(part);
    FASTNORM_CHECK(!parts.empty(), "solver: empty solver name");
    const std::string& kind = parts[0];
    auto number = [&](std::size_t at, int fallback, const char* what) {
      if (parts.size() <= at) return fallback;
      std::size_t used = 0;
      int value = 0;
      try {
        value = std::stoi(parts[at], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      FASTNORM_CHECK(used == parts[at].size() && used > 0,
                     "solver '" + name + "': " + what + " must be a whole number, not '" + parts[at] + "'");
      return value;
    };
    auto max_parts = [&](std::size_t count) {
      FASTNORM_CHECK(parts.size() <= count, "solver '" + name + "': too many ':' fields");
    };
    if (kind == "norm") {
      max_parts(1);
      adopt(NormSolver<Scalar>(grid, material, options), "norm");
    } else if (kind == "cg") {
      max_parts(1);
      adopt(CgSolver<Scalar>(grid, material), "cg");
    } else if (kind == "elliptic") {
      max_parts(1);
      adopt(ReducedSolver<EllipticBasis, Scalar>(grid, material, EllipticBasis(), options), kind);
    } else if (kind == "polynomial") {
      max_parts(2);
      const PolynomialBasis basis(number(1, 4, "the grade G"));
      adopt(ReducedSolver<PolynomialBasis, Scalar>(grid, material, basis, options), basis.name());
    } else if (kind == "elliptic-edge") {
      max_parts(2);
      const EllipticEdgeBasis basis(EllipticBasis(), number(1, 1, "the edge elements K"));
      adopt(ReducedSolver<EllipticEdgeBasis, Scalar>(grid, material, basis, options), basis.name());
    } else if (kind == "polynomial-edge") {
      max_parts(3);
      const PolynomialEdgeBasis basis(PolynomialBasis(number(1, 4, "the grade G")),
                                      number(2, 1, "the edge elements K"));
      adopt(ReducedSolver<PolynomialEdgeBasis, Scalar>(grid, material, basis, options), basis.name());
    } else {
      FASTNORM_CHECK(false, "unknown solver '" + name +
                                "' (known: norm, cg, elliptic, polynomial[:G], elliptic-edge[:K], "
                                "polynomial-edge[:G[:K]])");
    }
  }

  AnySolver(const AnySolver& other) : model_(other.model_->clone()), name_(other.name_) {}
  AnySolver& operator=(const AnySolver& other) {
    if (this != &other) *this = AnySolver(other);
    return *this;
  }
  AnySolver(AnySolver&&) noexcept = default;
  AnySolver& operator=(AnySolver&&) noexcept = default;
  ~AnySolver() = default;

  /// The canonical name, with defaults filled in (e.g. "polynomial:4").
  const std::string& name() const { return name_; }

  /// As NormSolver::solve: a cold solve.
  Solution<Scalar> solve(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading) const {
    return model_->solve(undeformed_distance, loading);
  }

  /// As NormSolver::solve_next: warm-started from the previous solve_next of this object.
  Solution<Scalar> solve_next(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading) {
    return model_->solve_next(undeformed_distance, loading);
  }

  /// The next solve_next starts cold.
  void reset() { model_->reset(); }

 private:
  struct Model {
    virtual ~Model() = default;
    virtual Solution<Scalar> solve(const Eigen::Ref<const Vector>& h, const Loading<Scalar>& loading) const = 0;
    virtual Solution<Scalar> solve_next(const Eigen::Ref<const Vector>& h, const Loading<Scalar>& loading) = 0;
    virtual void reset() = 0;
    virtual std::unique_ptr<Model> clone() const = 0;
  };

  template <typename Solver>
  struct Holder final : Model {
    explicit Holder(Solver held) : solver(std::move(held)) {}
    Solution<Scalar> solve(const Eigen::Ref<const Vector>& h, const Loading<Scalar>& loading) const override {
      return solver.solve(h, loading);
    }
    Solution<Scalar> solve_next(const Eigen::Ref<const Vector>& h, const Loading<Scalar>& loading) override {
      return solver.solve_next(h, loading);
    }
    void reset() override { solver.reset(); }
    std::unique_ptr<Model> clone() const override { return std::make_unique<Holder>(solver); }
    Solver solver;
  };

  template <typename Solver>
  void adopt(Solver solver, const std::string& name) {
    model_ = std::make_unique<Holder<Solver>>(std::move(solver));
    name_ = name;
  }

  std::unique_ptr<Model> model_;
  std::string name_;
};

}  // namespace fastnorm
