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
#include <string>
#include <vector>

#include "fastnorm/active_set.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/fft_convolution.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"

namespace fastnorm {

/// Settings of the conjugate-gradient solver.
template <typename Scalar = double>
struct CgOptions {
  /// Stop when the complementarity error (docs/performance.md Eq. (P1)) — the largest
  /// |gap| where p > 0 and the largest interpenetration where p = 0 — is at most
  /// `tolerance` times the largest interpenetration of the undeformed surfaces.
  Scalar tolerance = Scalar(1e-9);
  /// Most iterations (products C t) before Status::iteration_limit.
  int max_iterations = 5000;

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    FASTNORM_CHECK(std::isfinite(tolerance) && tolerance > 0,
                   detail::describe("options: tolerance must be positive and finite", tolerance));
    FASTNORM_CHECK(max_iterations >= 1,
                   detail::describe("options: max_iterations must be >= 1", max_iterations));
  }
};

/// The Signorini problem g = h − δ + C p ≥ 0, p ≥ 0, g·p = 0 by bound-constrained
/// conjugate gradients on the whole grid, approach or force control.
///
/// `solve` is cold and const (safe to call from several threads). `solve_next` starts from
/// the pressures of the previous `solve_next` on this object and reuses its FFT workspace:
/// the call to make at every time step of a simulation.
///
/// **Example**
/// @code
/// fastnorm::CgSolver<> solver(grid, fastnorm::Material<>(2.1e11, 0.3));
/// auto solution = solver.solve(h, fastnorm::Loading<>::force(1e5));
/// @endcode
template <typename Scalar = double>
class CgSolver {
 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Options = CgOptions<Scalar>;

  /// @throws fastnorm::invalid_argument for invalid options
  CgSolver(const Grid<Scalar>& grid, const Material<Scalar>& material, Options options = {})
      : influence_(grid, material), options_(options), workspace_(influence_) {
    options_.validate();
  }

  const Grid<Scalar>& grid() const { return influence_.grid(); }
  const InfluenceTable<Scalar>& influence() const { return influence_; }
  const Options& options() const { return options_; }

  /// As NormSolver::solve. Solution::iterations counts conjugate-gradient iterations.
  /// @throws fastnorm::invalid_argument for wrong sizes or non-finite h
  Solution<Scalar> solve(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading) const {
    Workspace workspace(workspace_.convolution);
    return run(workspace, undeformed_distance, loading, false);
  }

  /// As solve, starting from the pressures of the previous solve_next (cold on the first
  /// call and after reset()).
  Solution<Scalar> solve_next(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading) {
    return run(workspace_, undeformed_distance, loading, true);
  }

  /// Forgets the previous pressures: the next solve_next starts cold.
  void reset() { workspace_.has_start = false; }

 private:
  /// Everything an iteration touches, allocated once.
  struct Workspace {
    explicit Workspace(const FftConvolution<Scalar>& prototype) : convolution(prototype) {}
    explicit Workspace(const InfluenceTable<Scalar>& influence) : convolution(influence) {}
    FftConvolution<Scalar> convolution;
    Vector pressure, displacement, gap, direction, product;
    std::vector<Index> corrected;  // elements whose step was clipped or that joined
    bool has_start = false;
  };

  /// Up to this many clipped or joining elements per iteration, C p is updated directly
  /// (cost N each) instead of by a new FFT product (docs/performance.md §2).
  static constexpr std::size_t max_direct_corrections = 32;

  Solution<Scalar> run(Workspace& work, const Eigen::Ref<const Vector>& h, const Loading<Scalar>& loading,
                       bool warm) const {
    const Grid<Scalar>& grid = influence_.grid();
    detail::check_undeformed_distance(grid, h);
    const bool force_control = loading.control == Control::force;
    if (force_control) Loading<Scalar>::force(loading.normal_force);  // validates Fn
    const Index n = grid.size();
    const Scalar area = grid.element_area();
    Vector& p = work.pressure;
    Vector& u = work.displacement;  // C p, kept up to date
    Vector& gap = work.gap;
    Vector& t = work.direction;
    Vector& r = work.product;  // C t
    if (gap.size() != n) {
      u.resize(n);
      gap.resize(n);
      t.resize(n);
      r.resize(n);
      work.corrected.reserve(max_direct_corrections);
    }

    Solution<Scalar> solution;
    const Scalar deepest = h.minCoeff();
    if (!force_control && deepest >= 0) {
      work.has_start = false;
      solution.pressure = Vector::Zero(n);
      solution.in_contact = Solution<Scalar>::Mask::Constant(n, false);
      solution.status = Status::no_contact;
      solution.message = "no element has a negative undeformed distance";
      return solution;
    }

    // Start: the previous pressures, or uniform pressure on the Hertz-like overlap.
    if (!(warm && work.has_start && p.size() == n && p.sum() > 0)) {
      const Scalar approach = force_control ? detail::approach_guess<Scalar>(h, area, influence_.combined_modulus(),
                                                                     loading.normal_force)
                                            : Scalar(0);
      p = (h.array() < approach).template cast<Scalar>().matrix();
      if (!force_control) {
        // Scale so the mean displacement over the overlap matches its mean depth.
        work.convolution.apply(p, u);
        p *= -h.cwiseMin(Scalar(0)).sum() / u.dot(p);
      }
    }
    if (force_control) p *= loading.normal_force / (area * p.sum());
    work.convolution.apply(p, u);

    const Scalar zero = 0;
    Scalar previous_norm = 1, approach = 0;
    bool restart = true, fresh = true;  // fresh: u was computed by FFT, not updated
    int iteration = 0;
    for (;;) {
      // The gap of the current pressures and, in force control, δ = mean over the contact.
      gap = h + u;
      Index contact = 0;
      approach = 0;
      if (force_control) {
        for (Index k = 0; k < n; ++k) {
          if (p(k) > zero) {
            approach += gap(k);
            ++contact;
          }
        }
        approach /= static_cast<Scalar>(contact);
        gap.array() -= approach;
      }
      // Complementarity error, Eq. (P1); judged only on a freshly computed C p.
      Scalar error = 0;
      for (Index k = 0; k < n; ++k) error = std::max(error, p(k) > zero ? std::abs(gap(k)) : -gap(k));
      const Scalar depth = approach - deepest;
      if (error <= options_.tolerance * depth) {
        if (fresh) break;
        work.convolution.apply(p, u);
        fresh = true;
        continue;
      }
      if (iteration == options_.max_iterations) {
        solution.status = Status::iteration_limit;
        solution.message = "complementarity error " + std::to_string(error / depth) + " after " +
                           std::to_string(iteration) + " iterations";
        break;
      }
      ++iteration;

      // Conjugate direction on the contact set (the gap there is its residual).
      Scalar norm = 0;
      for (Index k = 0; k < n; ++k) {
        if (p(k) > zero) norm += gap(k) * gap(k);
      }
      const Scalar beta = restart ? Scalar(0) : norm / previous_norm;
      previous_norm = norm;
      for (Index k = 0; k < n; ++k) t(k) = p(k) > zero ? gap(k) + beta * t(k) : zero;
      work.convolution.apply(t, r);
      Scalar r_mean = 0;
      if (force_control) {
        for (Index k = 0; k < n; ++k) {
          if (p(k) > zero) r_mean += r(k);
        }
        r_mean /= static_cast<Scalar>(contact);
      }
      Scalar gt = 0, rt = 0;
      for (Index k = 0; k < n; ++k) {
        if (p(k) > zero) {
          gt += gap(k) * t(k);
          rt += (r(k) - r_mean) * t(k);
        }
      }
      const Scalar step = gt / rt;
      // Step, projection on p ≥ 0, and the elements that interpenetrate join with −step·g.
      // u follows as u − step·r plus C times what the projection and the joins changed.
      restart = false;
      work.corrected.clear();
      bool overflow = false;
      auto correct = [&](Index k) {
        if (work.corrected.size() < max_direct_corrections) work.corrected.push_back(k); else overflow = true;
      };
      for (Index k = 0; k < n; ++k) {
        if (p(k) > zero) {
          p(k) -= step * t(k);
          if (p(k) < zero) correct(k);
        } else if (gap(k) < zero) {
          p(k) = -step * gap(k);
          restart = true;
          correct(k);
        }
      }
      if (overflow) {
        p = p.cwiseMax(zero);
        work.convolution.apply(p, u);
        fresh = true;
      } else {
        u -= step * r;
        for (Index k : work.corrected) {
          // Clipped: p went below 0 by the step, C(·, k) adds back −p_k. Joined: adds p_k.
          const Scalar change = t(k) != zero ? -p(k) : p(k);
          if (t(k) != zero) p(k) = zero;
          influence_.add_displacement(k, change, u);
        }
        fresh = false;
      }
      if (force_control) {
        const Scalar scale = loading.normal_force / (area * p.sum());
        p *= scale;
        u *= scale;
      }
    }

    work.has_start = true;
    solution.pressure = p;
    solution.in_contact = p.array() > zero;
    solution.normal_force = area * p.sum();
    solution.approach = force_control ? approach : Scalar(0);
    solution.iterations = iteration;
    if (solution.status == Status::converged) solution.message = "complementarity error below tolerance";
    return solution;
  }

  InfluenceTable<Scalar> influence_;
  Options options_;
  Workspace workspace_;
};

}  // namespace fastnorm
