#pragma once
/// @file cg_solver.hpp
/// The matrix-free full solver: bound-constrained conjugate gradients for the Signorini
/// problem (Polonsky and Keer, Wear 231, 1999) preconditioned by an FFT approximate inverse
/// of C, as Vollebregt's BCCG (J. Comput. Phys. 257, 2014), with C p by FFT
/// (fft_convolution.hpp). Memory and time per iteration grow as N and N log N, where dense
/// NORM needs N² memory and N³ time; the iterations hardly grow with N (docs/performance.md
/// §2, §9).

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

/// What a CgSolver keeps between solves: the starting pressures, its FFT plans and buffers
/// (of C and of the preconditioner), and the iteration's vectors, all allocated on the
/// first solve. One per thread.
template <typename Scalar = double>
class CgWorkspace {
 public:
  CgWorkspace() = default;
  CgWorkspace(const CgWorkspace& other) { *this = other; }
  /// A copy holds what the next solve reads, the start; the FFT plans and buffers, copies of
  /// a solver's, stay this workspace's own when they are of the same kernel as the other's,
  /// and the iteration's vectors are this workspace's storage (sized by each solve). A time
  /// loop's trial steps copy workspaces often (WheelsetContact::restore).
  CgWorkspace& operator=(const CgWorkspace& other) {
    if (this == &other) return *this;
    start_ = other.start_;
    if (!other.convolution_) {
      convolution_.reset(), preconditioner_.reset();
    } else if (!convolution_ || !convolution_->same_kernel(*other.convolution_)) {
      convolution_ = other.convolution_, preconditioner_ = other.preconditioner_;
    }
    return *this;
  }
  CgWorkspace(CgWorkspace&&) noexcept = default;
  CgWorkspace& operator=(CgWorkspace&&) noexcept = default;
  ~CgWorkspace() = default;

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
  // Copies of the solver's C and K.
  std::optional<FftConvolution<Scalar>> convolution_, preconditioner_;
  Vector pressure_, displacement_, gap_, direction_, product_;
  Vector residual_, previous_residual_, preconditioned_;  // w, the last w, z = K w
  std::vector<Eigen::Index> corrected_;  // elements whose step was clipped
  std::vector<Scalar> sorted_distance_;  // of the force-control starting guess
  Solution<Scalar> spare_solution_;      // storage for the next answer (recycle)
};

/// The Signorini problem g = h − δ + C p ≥ 0, p ≥ 0, g·p = 0 by preconditioned
/// bound-constrained conjugate gradients on the whole grid, approach or force control
/// (docs/performance.md §9).
///
/// `solve(h, loading, workspace)` starts from the workspace's pressures (from a Hertz-like
/// pressure on its contact set, or on the overlap at half the depth, when it has none);
/// the answer is NORM's to the tolerance whatever the start.
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
        convolution_(std::make_shared<const FftConvolution<Scalar>>(*influence_)),
        preconditioner_(std::make_shared<const FftConvolution<Scalar>>(
            FftConvolution<Scalar>::approximate_inverse(*influence_))) {
    options_.validate();
  }

  const Grid<Scalar>& grid() const { return influence_->grid(); }
  const InfluenceTable<Scalar>& influence() const { return *influence_; }
  const Options& options() const { return options_; }

  /// As NormSolver::solve. Solution::iterations counts conjugate-gradient iterations (two
  /// FFT products each: the preconditioner's and C's), Solution::residual is the
  /// complementarity error of Eq. (P1) relative to the depth.
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
      // Every CG iterate is admissible, so it stops at the cap as at the limit.
      const IterationStop stop = workspace.start_.stop(options_.max_iterations);
      Options options = options_;
      options.max_iterations = stop.soft;
      Iteration iteration{*influence_, options, undeformed_distance, loading, workspace, stop.budget};
      iteration.start();
      iteration.run(solution);
    }
    detail::check_answer(solution, grid.mx(), grid.my(), grid.element_area(), loading);
    workspace.start_.remember_pressure(solution);
    return solution;
  }

  /// The normal stiffness dFn/dδ (N/m) of the discrete problem at the contact set I of
  /// `solution`: area · 1ᵀ x with C_II x = 1, by conjugate gradients on I preconditioned
  /// by K (C_II is symmetric positive definite), to a residual of options().tolerance
  /// relative to 1 (docs/norm.md §4). NaN if that does not converge within max_iterations.
  Scalar normal_stiffness(const Solution<Scalar>& solution, Workspace& work) const {
    FASTNORM_CHECK(solution.in_contact.size() == grid().size(), "CgSolver::normal_stiffness: solution of another grid");
    prepare(work);
    Vector& x = work.pressure_;
    Vector& residual = work.gap_;
    Vector& preconditioned = work.preconditioned_;
    Vector& direction = work.direction_;
    Vector& product = work.product_;
    const auto on_set = solution.in_contact.template cast<Scalar>();  // 1 on I, 0 elsewhere
    if (!solution.in_contact.any()) return Scalar(0);
    x.setZero();
    residual = on_set.matrix();
    const Scalar target = options_.tolerance * options_.tolerance * residual.squaredNorm();
    Scalar residual_dot_preconditioned = 0;
    for (int iteration = 0; residual.squaredNorm() > target; ++iteration) {
      if (iteration == options_.max_iterations) return std::numeric_limits<Scalar>::quiet_NaN();
      work.preconditioner_->apply(residual, preconditioned);
      preconditioned.array() *= on_set;
      const Scalar next = residual.dot(preconditioned);
      if (iteration == 0) direction = preconditioned;
      else direction = preconditioned + (next / residual_dot_preconditioned) * direction;
      residual_dot_preconditioned = next;
      work.convolution_->apply(direction, product);
      product.array() *= on_set;
      const Scalar step = next / direction.dot(product);
      x += step * direction;
      residual -= step * product;
    }
    return grid().element_area() * x.sum();
  }

 private:
  /// Up to this many clipped elements per iteration, C p is updated directly (cost N
  /// each) instead of by a new FFT product (docs/performance.md §2).
  static constexpr std::size_t max_direct_corrections = 32;

  /// Gives the workspace this solver's convolutions and vectors of the grid's size.
  void prepare(Workspace& work) const {
    if (!work.convolution_ || !work.convolution_->same_kernel(*convolution_)) {
      work.convolution_.emplace(*convolution_);
      work.preconditioner_.emplace(*preconditioner_);
    }
    const Index n = grid().size();
    for (Vector* vector : {&work.pressure_, &work.displacement_, &work.gap_, &work.direction_, &work.product_,
                           &work.residual_, &work.previous_residual_, &work.preconditioned_}) {
      if (vector->size() != n) vector->resize(n);
    }
    work.corrected_.reserve(max_direct_corrections);
  }

  /// One solve: the state of the iteration and its steps (docs/performance.md §9). The
  /// free set F holds the elements in contact (p > 0) and those that interpenetrate
  /// (p = 0, g < 0); each iteration takes a conjugate direction on F from the
  /// preconditioned gap, steps along it and clips negative pressures.
  struct Iteration {
    const InfluenceTable<Scalar>& influence;
    const Options& options;
    const Eigen::Ref<const Vector>& h;
    const Loading<Scalar>& loading;
    Workspace& work;
    bool budgeted;  // options.max_iterations is a caller's budget or cap (WarmStart::stop)
    Vector& p = work.pressure_;
    Vector& u = work.displacement_;  // C p, kept up to date
    Vector& gap = work.gap_;
    Vector& w = work.residual_;  // the gap on F (less its mean over F in force control)
    Vector& z = work.preconditioned_;
    Vector& t = work.direction_;
    Vector& r = work.product_;  // C t
    bool force_control = loading.control == Control::force;
    Scalar area = influence.grid().element_area();
    Scalar deepest = h.minCoeff();
    Scalar approach = 0, previous_wz = 0;
    Index free_count = 0;  // elements in F this iteration
    bool first = true;  // no direction yet
    bool fresh = true;  // u was computed by FFT, not updated

    /// The starting pressures and u = C p: the workspace's pressures, or a Hertz-like shape
    /// (on the workspace's contact set, or on the overlap at half the depth) scaled to the
    /// least energy in approach control. In force control every start is scaled to the load.
    void start() {
      const WarmStart<Scalar>& from = work.start_;
      if (from.has_pressure()) {
        p = from.pressure();
      } else {
        if (!from.contact_set().empty()) hertz_like_on_set(from.contact_set());
        else hertz_like_on_overlap();
        if (!force_control) {
          scale_to_least_energy(Scalar(0));  // u = C p with it
          return;
        }
      }
      if (force_control) p *= loading.normal_force / (area * p.sum());
      work.convolution_->apply(p, u);
    }

    /// p = √(level − h) on the set, the level its highest h (+ the least normal number: that
    /// element starts in contact too).
    void hertz_like_on_set(const std::vector<Index>& set) {
      Scalar level = h(set.front());
      for (Index k : set) level = std::max(level, h(k));
      p.setZero();
      for (Index k : set) p(k) = std::sqrt(level - h(k)) + std::numeric_limits<Scalar>::min();
    }

    /// p ∝ √(level − h) where h < level = (δ + min h)/2: a Hertz contact's pressure on its
    /// contact area, which is the overlap at half the depth (docs/performance.md §9). δ is
    /// 0 in approach control; in force control the Hertz-like guess of docs/norm.md Eq. (N3),
    /// corrected once by Fn ∝ (δ − min h)^(3/2) from the force of that start.
    void hertz_like_on_overlap() {
      auto shape = [&](Scalar depth_to) {
        const Scalar level = (depth_to + deepest) / 2;
        p = (level - h.array()).cwiseMax(Scalar(0)).sqrt().matrix();
      };
      if (!force_control) {
        shape(Scalar(0));
        return;
      }
      const Scalar guess = detail::approach_guess<Scalar>(h, area, influence.combined_modulus(), loading.normal_force,
                                                          work.sorted_distance_);
      shape(guess);
      scale_to_least_energy(guess);
      const Scalar force = area * p.sum();
      if (force > 0) shape(deepest + (guess - deepest) * std::pow(loading.normal_force / force, Scalar(2) / 3));
    }

    /// Scales p, and u = C p with it, to the least energy ½ pᵀC p + (h − δ)ᵀp along p.
    void scale_to_least_energy(Scalar depth_to) {
      work.convolution_->apply(p, u);
      const Scalar scale = std::max(Scalar(0), -(h.dot(p) - depth_to * p.sum()) / u.dot(p));
      p *= scale;
      u *= scale;
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
        // Nothing more to gain when the error or the depth it is measured against is not a
        // finite positive number: C p underflows or δ overflows (E near 1e100, Fn near 1e300).
        const Scalar depth = approach - deepest;
        if (!(std::isfinite(error) && std::isfinite(depth) && depth > 0)) {
          solution.status = Status::numerical_issue;
          solution.message = "the complementarity error or the depth is not finite after " +
                             std::to_string(iteration) + " iterations (modulus or force too large for the precision?)";
          break;
        }
        if (iteration == options.max_iterations) {
          if (budgeted) {
            // Every iterate is projected (p ≥ 0) and in force control scaled to the load, so
            // the answer is usable; a literal, since a budgeted time step allocates nothing.
            solution.status = Status::budget_reached;
            solution.message = "stopped by the iteration budget; the next solve goes on from here";
          } else {
            solution.status = Status::iteration_limit;
            solution.message = "complementarity error " + std::to_string(error / (approach - deepest)) + " after " +
                               std::to_string(iteration) + " iterations";
          }
          break;
        }
        ++iteration;
        precondition();
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
      approach = 0;
      if (force_control) {
        // Summed in at least double: in float the round-off of a sum over 10⁴ elements
        // would be above the tolerance.
        detail::KernelWork<Scalar> sum = 0;
        Index contact = 0;
        for (Index k = 0; k < p.size(); ++k) {
          if (p(k) > 0) {
            sum += static_cast<detail::KernelWork<Scalar>>(gap(k));
            ++contact;
          }
        }
        approach = static_cast<Scalar>(sum / static_cast<detail::KernelWork<Scalar>>(contact));
        gap.array() -= approach;
      }
      Scalar error = 0;
      for (Index k = 0; k < p.size(); ++k) error = std::max(error, p(k) > 0 ? std::abs(gap(k)) : -gap(k));
      return error;
    }

    bool in_free_set(Index k) const { return p(k) > 0 || gap(k) < 0; }

    /// w = the gap on F and z = K w on F; in force control both with their mean over F
    /// taken out, so that steps along them keep Σp (the deflation of the constant).
    void precondition() {
      w.swap(work.previous_residual_);
      free_count = 0;
      for (Index k = 0; k < p.size(); ++k) {
        const bool free = in_free_set(k);
        w(k) = free ? gap(k) : Scalar(0);
        free_count += free;
      }
      remove_mean_on_free_set(w);
      work.preconditioner_->apply(w, z);
      for (Index k = 0; k < p.size(); ++k) {
        if (!in_free_set(k)) z(k) = 0;
      }
      remove_mean_on_free_set(z);
    }

    /// In force control: `vector` (0 off F) less its mean over F, on F.
    void remove_mean_on_free_set(Vector& vector) const {
      if (!force_control) return;
      const Scalar mean = vector.sum() / static_cast<Scalar>(free_count);
      for (Index k = 0; k < p.size(); ++k) {
        if (in_free_set(k)) vector(k) -= mean;
      }
    }

    /// t = z + β t on F, in force control less its mean. β by Polak and Ribière, at least
    /// 0, with no restart when the contact set changes: the formula restarts by itself
    /// (β ≈ 0) when the new gap is far from conjugate to the last, and keeps the directions
    /// when a few edge elements change (restarting there made a 960² case zigzag;
    /// docs/performance.md §9).
    void conjugate_direction() {
      const Scalar wz = w.dot(z);
      const Scalar beta =
          first ? Scalar(0) : std::max(Scalar(0), (wz - work.previous_residual_.dot(z)) / previous_wz);
      previous_wz = wz;
      for (Index k = 0; k < p.size(); ++k) {
        // On the first iteration t holds nothing yet.
        t(k) = !in_free_set(k) ? Scalar(0) : first ? z(k) : z(k) + beta * t(k);
      }
      remove_mean_on_free_set(t);
    }

    /// r = C t and the step along t that minimises the energy (t is 0 off F; in force
    /// control Σt = 0, so δ drops out).
    Scalar step_length() {
      work.convolution_->apply(t, r);
      const Scalar curvature = r.dot(t);
      return curvature > 0 ? gap.dot(t) / curvature : Scalar(0);
    }

    /// Step along −t, projection on p ≥ 0; an element of F with p = 0 joins when the step
    /// gives it pressure. u follows as u − step·r plus C times what the projection changed.
    void take_step(Scalar step) {
      first = false;
      work.corrected_.clear();
      bool overflow = false;
      for (Index k = 0; k < p.size(); ++k) {
        if (t(k) == 0) continue;
        p(k) -= step * t(k);
        if (p(k) < 0) {
          if (work.corrected_.size() < max_direct_corrections) work.corrected_.push_back(k); else overflow = true;
        }
      }
      if (overflow) {
        p = p.cwiseMax(Scalar(0));
        work.convolution_->apply(p, u);
        fresh = true;
      } else {
        u -= step * r;
        for (Index k : work.corrected_) {
          influence.add_displacement(k, -p(k), u);  // the clip adds −p_k on element k
          p(k) = 0;
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
  // Copied into each workspace: C (zero-padded) and its approximate inverse K.
  std::shared_ptr<const FftConvolution<Scalar>> convolution_;
  std::shared_ptr<const FftConvolution<Scalar>> preconditioner_;
};

}  // namespace fastnorm
