#pragma once
/// @file cg_solver.hpp
/// The matrix-free full solver: Polonsky and Keer's bound-constrained conjugate gradients
/// for the Signorini problem (Wear 231, 1999) with C p by FFT (fft_convolution.hpp).
/// Memory and time per iteration grow as N and N log N, where dense NORM needs N² memory
/// and N³ time (docs/performance.md §2).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fastnorm/detail/solver_base.hpp"
#include "fastnorm/detail/solver_input.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/fft_convolution.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/solver_options.hpp"
#include "fastnorm/warm_start.hpp"

namespace fastnorm {

template <typename Scalar>
class CgSolver;

/// What a CgSolver keeps between solves: the starting pressures, its FFT plans and buffers,
/// and the iteration's vectors, all allocated on the first solve. One per thread.
template <typename Scalar = double>
class CgWorkspace {
 public:
  /// Where the next solve starts; after a solve, its pressures and contact set.
  WarmStart<Scalar>& start() { return start_; }
  const WarmStart<Scalar>& start() const { return start_; }
  /// The next solve is cold (storage kept).
  void forget() { start_.clear(); }
  /// Storage for the next solve's answer: a Solution no longer needed (e.g. the previous
  /// answer of a time loop), handed back so that the next solve fills it instead of
  /// allocating its vectors.
  void recycle(Solution<Scalar>&& used) { spare_solution_ = std::move(used); }

 private:
  friend class CgSolver<Scalar>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  WarmStart<Scalar> start_;
  std::optional<FftConvolution<Scalar>> convolution_;  // a copy of the solver's
  Vector pressure_, displacement_, gap_, direction_, product_;
  std::vector<Eigen::Index> corrected_;  // elements whose step was clipped or that joined
  std::vector<Scalar> sorted_distance_;  // of the force-control starting guess
  Solution<Scalar> spare_solution_;      // storage for the next answer (recycle)
};

/// The Signorini problem g = h − δ + C p ≥ 0, p ≥ 0, g·p = 0 by bound-constrained
/// conjugate gradients on the whole grid, approach or force control.
///
/// `solve(h, loading, workspace)` starts from the workspace's pressures (from uniform
/// pressure on its contact set, or on a Hertz-like overlap, when it has none); the answer
/// is NORM's to the tolerance whatever the start.
///
/// **Example**
/// @code
/// fastnorm::CgSolver<> solver(grid, fastnorm::Material<>(2.1e11, 0.3));
/// auto solution = solver.solve(h, fastnorm::Loading<>::force(1e5));
/// @endcode
template <typename Scalar = double>
class CgSolver : public detail::SolverBase<CgSolver<Scalar>, CgWorkspace<Scalar>, Scalar> {
 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Options = CgOptions<Scalar>;
  using Workspace = CgWorkspace<Scalar>;
  using detail::SolverBase<CgSolver, Workspace, Scalar>::solve;

  /// @throws fastnorm::invalid_argument for invalid options
  CgSolver(const Grid<Scalar>& grid, const Material<Scalar>& material, Options options = {})
      : influence_(std::make_shared<const InfluenceTable<Scalar>>(grid, material)),
        options_(options),
        convolution_(std::make_shared<const FftConvolution<Scalar>>(*influence_)) {
    options_.validate();
  }

  const Grid<Scalar>& grid() const { return influence_->grid(); }
  const InfluenceTable<Scalar>& influence() const { return *influence_; }
  const Options& options() const { return options_; }

  /// As NormSolver::solve. Solution::iterations counts conjugate-gradient iterations,
  /// Solution::residual is the complementarity error of Eq. (P1) relative to the depth.
  /// @throws fastnorm::invalid_argument for wrong sizes, non-finite h, a bad Fn or a bad start
  Solution<Scalar> solve(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading,
                         Workspace& workspace) const {
    const Grid<Scalar>& grid = influence_->grid();
    detail::check_problem(grid, undeformed_distance, loading);
    workspace.start_.check(grid.size());
    prepare(workspace);
    Solution<Scalar> solution = std::move(workspace.spare_solution_);
    solution.clear(grid.size());
    if (loading.control == Control::approach && undeformed_distance.minCoeff() >= 0) {
      solution.status = Status::no_contact;
      solution.message = "no element has a negative undeformed distance";
    } else {
      Iteration iteration{*influence_, options_, undeformed_distance, loading, workspace};
      iteration.start();
      iteration.run(solution);
    }
    workspace.start_.remember_pressure(solution);
    return solution;
  }

  /// The normal stiffness dFn/dδ (N/m) of the discrete problem at the contact set I of
  /// `solution`: area · 1ᵀ x with C_II x = 1, by conjugate gradients on I with C by FFT
  /// (C_II is symmetric positive definite), to a residual of options().tolerance relative
  /// to 1 (docs/norm.md §4). NaN if that does not converge within max_iterations.
  Scalar normal_stiffness(const Solution<Scalar>& solution, Workspace& work) const {
    FASTNORM_CHECK(solution.in_contact.size() == grid().size(), "CgSolver::normal_stiffness: solution of another grid");
    prepare(work);
    Vector& x = work.pressure_;
    Vector& residual = work.gap_;
    Vector& direction = work.direction_;
    Vector& product = work.product_;
    const auto on_set = solution.in_contact.template cast<Scalar>();  // 1 on I, 0 elsewhere
    if (!solution.in_contact.any()) return Scalar(0);
    x.setZero();
    residual = on_set.matrix();
    direction = residual;
    const Scalar target = options_.tolerance * options_.tolerance * residual.squaredNorm();
    Scalar norm = residual.squaredNorm();
    for (int iteration = 0; norm > target; ++iteration) {
      if (iteration == options_.max_iterations) return std::numeric_limits<Scalar>::quiet_NaN();
      work.convolution_->apply(direction, product);
      product.array() *= on_set;
      const Scalar step = norm / direction.dot(product);
      x += step * direction;
      residual -= step * product;
      const Scalar next = residual.squaredNorm();
      direction = residual + (next / norm) * direction;
      norm = next;
    }
    return grid().element_area() * x.sum();
  }

 private:
  /// Up to this many clipped or joining elements per iteration, C p is updated directly
  /// (cost N each) instead of by a new FFT product (docs/performance.md §2).
  static constexpr std::size_t max_direct_corrections = 32;

  /// Gives the workspace this solver's convolution and vectors of the grid's size.
  void prepare(Workspace& work) const {
    if (!work.convolution_ || !work.convolution_->same_kernel(*convolution_)) work.convolution_.emplace(*convolution_);
    const Index n = grid().size();
    for (Vector* vector : {&work.pressure_, &work.displacement_, &work.gap_, &work.direction_, &work.product_}) {
      if (vector->size() != n) vector->resize(n);
    }
    work.corrected_.reserve(max_direct_corrections);
  }

  /// One solve: the state of the iteration and its steps.
  struct Iteration {
    const InfluenceTable<Scalar>& influence;
    const Options& options;
    const Eigen::Ref<const Vector>& h;
    const Loading<Scalar>& loading;
    Workspace& work;
    Vector& p = work.pressure_;
    Vector& u = work.displacement_;  // C p, kept up to date
    Vector& gap = work.gap_;
    Vector& t = work.direction_;
    Vector& r = work.product_;  // C t
    bool force_control = loading.control == Control::force;
    Scalar area = influence.grid().element_area();
    Scalar deepest = h.minCoeff();
    Scalar approach = 0, previous_norm = 1;
    Index contact = 0;
    bool restart = true, fresh = true;  // fresh: u was computed by FFT, not updated

    /// The starting pressures: the workspace's, uniform on its contact set, or uniform on the
    /// Hertz-like overlap; then C p.
    void start() {
      const WarmStart<Scalar>& from = work.start_;
      if (from.has_pressure()) {
        p = from.pressure();
      } else {
        if (!from.contact_set().empty()) {
          p.setZero();
          for (Index k : from.contact_set()) p(k) = 1;
        } else {
          const Scalar guess = force_control ? detail::approach_guess<Scalar>(h, area, influence.combined_modulus(),
                                                                             loading.normal_force, work.sorted_distance_)
                                             : Scalar(0);
          p = (h.array() < guess).template cast<Scalar>().matrix();
        }
        if (!force_control) {
          // Scale so the mean displacement over the overlap matches its mean depth.
          work.convolution_->apply(p, u);
          p *= -h.cwiseMin(Scalar(0)).sum() / u.dot(p);
        }
      }
      if (force_control) p *= loading.normal_force / (area * p.sum());
      work.convolution_->apply(p, u);
    }

    /// The loop: complementarity error judged only on a freshly computed C p.
    void run(Solution<Scalar>& solution) {
      solution.status = Status::converged;
      solution.message = "complementarity error below tolerance";
      int iteration = 0;
      Scalar error = 0;
      for (;;) {
        error = gap_and_error();
        if (error <= options.tolerance * (approach - deepest)) {
          if (fresh) break;
          work.convolution_->apply(p, u);
          fresh = true;
          continue;
        }
        if (iteration == options.max_iterations) {
          solution.status = Status::iteration_limit;
          solution.message = "complementarity error " + std::to_string(error / (approach - deepest)) + " after " +
                             std::to_string(iteration) + " iterations";
          break;
        }
        ++iteration;
        conjugate_direction();
        take_step(step_length());
      }
      solution.pressure = p;
      solution.in_contact = p.array() > Scalar(0);  // same size: no allocation
      solution.normal_force = area * p.sum();
      solution.approach = force_control ? approach : Scalar(0);
      solution.iterations = iteration;
      solution.residual = error / (approach - deepest);
    }

    /// The gap of the current pressures and, in force control, δ = its mean over the
    /// contact; returns the complementarity error, Eq. (P1).
    Scalar gap_and_error() {
      gap = h + u;
      contact = 0;
      approach = 0;
      if (force_control) {
        for (Index k = 0; k < p.size(); ++k) {
          if (p(k) > 0) {
            approach += gap(k);
            ++contact;
          }
        }
        approach /= static_cast<Scalar>(contact);
        gap.array() -= approach;
      }
      Scalar error = 0;
      for (Index k = 0; k < p.size(); ++k) error = std::max(error, p(k) > 0 ? std::abs(gap(k)) : -gap(k));
      return error;
    }

    /// Conjugate direction t on the contact set (the gap there is its residual).
    void conjugate_direction() {
      Scalar norm = 0;
      for (Index k = 0; k < p.size(); ++k) {
        if (p(k) > 0) norm += gap(k) * gap(k);
      }
      const Scalar beta = restart ? Scalar(0) : norm / previous_norm;
      previous_norm = norm;
      // On a restart t holds nothing yet (uninitialised storage: 0·t could be NaN).
      for (Index k = 0; k < p.size(); ++k) t(k) = p(k) > 0 ? gap(k) + (restart ? Scalar(0) : beta * t(k)) : Scalar(0);
    }

    /// r = C t and the step along t that minimises the energy on the contact set (with the
    /// mean of r removed in force control, which keeps Σp fixed).
    Scalar step_length() {
      work.convolution_->apply(t, r);
      Scalar r_mean = 0;
      if (force_control) {
        for (Index k = 0; k < p.size(); ++k) {
          if (p(k) > 0) r_mean += r(k);
        }
        r_mean /= static_cast<Scalar>(contact);
      }
      Scalar gt = 0, rt = 0;
      for (Index k = 0; k < p.size(); ++k) {
        if (p(k) > 0) {
          gt += gap(k) * t(k);
          rt += (r(k) - r_mean) * t(k);
        }
      }
      return gt / rt;
    }

    /// Step, projection on p ≥ 0, and the elements that interpenetrate join with −step·g.
    /// u follows as u − step·r plus C times what the projection and the joins changed.
    void take_step(Scalar step) {
      restart = false;
      work.corrected_.clear();
      bool overflow = false;
      auto correct = [&](Index k) {
        if (work.corrected_.size() < max_direct_corrections) work.corrected_.push_back(k); else overflow = true;
      };
      for (Index k = 0; k < p.size(); ++k) {
        if (p(k) > 0) {
          p(k) -= step * t(k);
          if (p(k) < 0) correct(k);
        } else if (gap(k) < 0) {
          p(k) = -step * gap(k);
          restart = true;
          correct(k);
        }
      }
      if (overflow) {
        p = p.cwiseMax(Scalar(0));
        work.convolution_->apply(p, u);
        fresh = true;
      } else {
        u -= step * r;
        for (Index k : work.corrected_) {
          // Clipped: p went below 0 by the step, C(·, k) adds back −p_k. Joined: adds p_k.
          const Scalar change = t(k) != 0 ? -p(k) : p(k);
          if (t(k) != 0) p(k) = 0;
          influence.add_displacement(k, change, u);
        }
        fresh = false;
      }
      if (force_control) {
        const Scalar scale = loading.normal_force / (area * p.sum());
        p *= scale;
        u *= scale;
      }
    }
  };

  std::shared_ptr<const InfluenceTable<Scalar>> influence_;
  Options options_;
  std::shared_ptr<const FftConvolution<Scalar>> convolution_;  // copied into each workspace
};

}  // namespace fastnorm
