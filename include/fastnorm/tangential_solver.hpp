#pragma once
/// @file tangential_solver.hpp
/// Steady rolling with Coulomb friction on a normal solution: the tractions, adhesion and
/// slip areas and creep forces of a patch for given creepages, by Gauss–Seidel sweeps over
/// the elements from the leading edge (docs/tangential.md §5–7). The reference path of the
/// tangential problem, as NORM is of the normal one.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fastnorm/constants.hpp"
#include "fastnorm/detail/anderson_mixing.hpp"
#include "fastnorm/detail/memory_check.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/fft_convolution.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/tangential_influence.hpp"
#include "fastnorm/tangential_problem.hpp"

namespace fastnorm {

/// When the sweeps of the exact tangential path stop (docs/tangential.md §7): the measure of
/// a sweep's traction changes that TangentialOptions::tolerance bounds, and that
/// TangentialSolution::residual reports.
enum class TangentialStop {
  /// No traction changed by more than tolerance · μ·max p_n in a sweep (fastnorm's default).
  largest_change,
  /// The root mean square of a sweep's traction changes over the contact is at most
  /// tolerance times that of the tractions: CONTACT's rule for its Gauss–Seidel solvers,
  /// whose EPS is the tolerance (10⁻⁵ in its wheel–rail runs, 10⁻⁶ in its Hertzian examples).
  rms_change,
};

template <typename Scalar = double>
struct TangentialOptions {
  /// The sweeps stop when the measure `stop` of a sweep's traction changes is at most this.
  /// The default: default_tolerance (constants.hpp).
  Scalar tolerance = default_tolerance<Scalar>;
  TangentialStop stop = TangentialStop::largest_change;
  int max_sweeps = 2000;
  void validate() const {
    FASTNORM_CHECK(tolerance > 0 && tolerance < 1,
                   detail::describe("TangentialOptions: tolerance must lie in (0, 1)", tolerance));
    FASTNORM_CHECK(max_sweeps >= 1, detail::describe("TangentialOptions: max_sweeps must be >= 1", max_sweeps));
  }
};

namespace detail {

/// The steady-rolling operator in difference variables. With q_K = p_K − p_K⁺ the traction
/// of an element minus its upstream neighbour's (the element on the leading-edge side; p is
/// zero outside the contact, so an exterior element just downstream of contact carries
/// q = −p of its upstream neighbour), the elastic part of the slip is
/// (u_I − u_I⁺)/dx = Σ_K C(I − K) q_K/dx (docs/tangential.md Eq. (T7)), and in the tractions
/// themselves Σ_K D(I − K) p_K with D(di) = [C(di) − C(di + e)]/dx (T6), e = `shift` the
/// step towards the leading edge. Stored: C/dx for every offset |di| ≤ mx, |dj| ≤ my − 1,
/// column-major in di (a q just beyond the grid's downstream edge is mx away from the far
/// column); D is the difference of two entries of a column.
template <typename Scalar>
struct RollingOperator {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  Eigen::Index mx = 0, my = 0, shift = 1;
  Matrix xx, xy, yy;  // C/dx, (2mx + 1) × (2my − 1): row mx + di, column my − 1 + dj

  RollingOperator(const TangentialInfluenceTable<Scalar>& influence, RollingDirection direction)
      : mx(influence.grid().mx()),
        my(checked_rows(influence.grid())),
        shift(direction == RollingDirection::positive_x ? 1 : -1),
        xx(2 * mx + 1, 2 * my - 1),
        xy(2 * mx + 1, 2 * my - 1),
        yy(2 * mx + 1, 2 * my - 1) {
    const Scalar dx = influence.grid().dx();
    for (Eigen::Index dj = -(my - 1); dj <= my - 1; ++dj) {
      for (Eigen::Index di = -mx; di <= mx; ++di) {
        const auto c = influence.coefficients(di, dj);  // |di| = mx: one element past the table
        xx(mx + di, my - 1 + dj) = c.xx / dx;
        xy(mx + di, my - 1 + dj) = c.xy / dx;
        yy(mx + di, my - 1 + dj) = c.yy / dx;
      }
    }
  }

 private:
  /// my, once the three tables are known to fit the machine's memory.
  static Eigen::Index checked_rows(const Grid<Scalar>& grid) {
    check_memory(3 * (2 * static_cast<double>(grid.mx()) + 1) * (2 * static_cast<double>(grid.my()) - 1), sizeof(Scalar),
                 "SteadyRollingSolver: grid mx x my");
    return grid.my();
  }
};

/// D p along the rows of a contact's bounding box by one-dimensional FFTs
/// (docs/tangential.md §7). For each offset dj between a target row and a source row, the
/// part of D p that a row's tractions give another row is a Toeplitz product along x with
/// D(·, dj). D is C's difference, so on a line of N ≥ 2L + 1 points (L the box's width) that
/// holds C(di, dj)/dx for |di| ≤ L its transform is (1 − e^{2πi e k/N}) times C's, and the
/// product is a circular convolution, diagonal in the row's half spectrum, that is exact on
/// the box's columns (what wraps around falls outside them). C_xx and C_yy are even in di,
/// C_xy is odd: their transforms are real, real and imaginary. The sweeps keep every contact
/// row's D p as that spectrum; a finished row's change is transformed and multiplied by the
/// difference's factor once, then added to every row (16 operations a frequency and row
/// pair; the direct update costs 6·L a source element and row pair), and a row is
/// transformed back when the sweep reaches it.
///
/// Spectra are stored as real and imaginary parts apart (the products then need no
/// shuffling of complex pairs, and the sweeps' Anderson mixing sees real numbers): a row's
/// is 4F values, F = N/2 + 1 frequencies, [Re x, Im x, Re y, Im y] of its D p's two
/// components or of a change's two traction components.
template <typename Scalar>
class RowSpectra {
 public:
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// The box: `columns` grid columns from `first_column`, `rows` grid rows.
  RowSpectra(const RollingOperator<Scalar>& rolling, Index first_column, Index columns, Index rows)
      : first_column_(first_column),
        columns_(columns),
        rows_(rows),
        length_(smooth_fft_length(2 * columns + 1, 4)),  // ≥ 2L + 1, a multiple of 4 (kissfft's fast real path)
        frequencies_(length_ / 2 + 1),
        fft_(half_spectrum_fft<Scalar>()),
        kernels_(3 * frequencies_, 2 * rows - 1),
        difference_re_(frequencies_),
        difference_im_(frequencies_),
        line_(length_),
        spectrum_(static_cast<std::size_t>(frequencies_)) {
    // Kernel of offset dj: C(di, dj)/dx at di mod N for |di| ≤ L, made exactly even (xx, yy)
    // or odd (xy) from its di ≥ 0 half; the inverse transform's 1/N folded in.
    const Scalar scale = Scalar(1) / static_cast<Scalar>(length_);
    const Matrix* tables[3] = {&rolling.xx, &rolling.xy, &rolling.yy};
    for (Index dj = -(rows - 1); dj < rows; ++dj) {
      for (Index table = 0; table < 3; ++table) {
        const Scalar odd = table == 1 ? Scalar(-1) : Scalar(1);
        line_.setZero();
        for (Index di = 0; di <= columns; ++di) {
          const Scalar value = scale * (*tables[table])(rolling.mx + di, rolling.my - 1 + dj);
          line_(di) = value;
          if (di > 0) line_(length_ - di) = odd * value;
        }
        fft_.fwd(spectrum_.data(), line_.data(), length_);
        auto kernel = kernels_.col(rows - 1 + dj).segment(table * frequencies_, frequencies_);
        for (Index f = 0; f < frequencies_; ++f) {
          const auto& value = spectrum_[static_cast<std::size_t>(f)];
          kernel(f) = table == 1 ? value.imag() : value.real();
        }
      }
    }
    // (1 − e^{2πi e k/N}): the transform of C(di) − C(di + e) over C's.
    const Scalar turn = 2 * pi<Scalar> * static_cast<Scalar>(rolling.shift) / static_cast<Scalar>(length_);
    for (Index f = 0; f < frequencies_; ++f) {
      difference_re_(f) = 1 - std::cos(turn * static_cast<Scalar>(f));
      difference_im_(f) = -std::sin(turn * static_cast<Scalar>(f));
    }
  }

  /// The values a row's spectrum holds (4F).
  Index spectrum_size() const { return 4 * frequencies_; }

  /// The spectra [Re x, Im x, Re y, Im y] of a change of a row's two traction components on
  /// the box's columns (`x` and `y` point at the row's column 0), times D's factor: what add
  /// takes.
  void forward_change(const Scalar* x, const Scalar* y, Eigen::Ref<Vector> spectra) {
    for (Index component = 0; component < 2; ++component) {
      line_.head(columns_) = Eigen::Map<const Vector>((component == 0 ? x : y) + first_column_, columns_);
      line_.tail(length_ - columns_).setZero();
      fft_.fwd(spectrum_.data(), line_.data(), length_);
      const Index at = 2 * component * frequencies_;
      for (Index f = 0; f < frequencies_; ++f) {
        const auto& value = spectrum_[static_cast<std::size_t>(f)];
        spectra(at + f) = value.real() * difference_re_(f) - value.imag() * difference_im_(f);
        spectra(at + frequencies_ + f) = value.real() * difference_im_(f) + value.imag() * difference_re_(f);
      }
    }
  }

  /// A row's two components on the box's columns from their spectra (`x` and `y` point at
  /// the row's column 0).
  void inverse(const Eigen::Ref<const Vector>& spectra, Scalar* x, Scalar* y) {
    for (Index component = 0; component < 2; ++component) {
      const Index at = 2 * component * frequencies_;
      for (Index f = 0; f < frequencies_; ++f) {
        spectrum_[static_cast<std::size_t>(f)] = {spectra(at + f), spectra(at + frequencies_ + f)};
      }
      fft_.inv(line_.data(), spectrum_.data(), length_);
      Eigen::Map<Vector>((component == 0 ? x : y) + first_column_, columns_) = line_.head(columns_);
    }
  }

  /// Adds to `target_spectra` (of box row `target`) what a change of box row `source`,
  /// with spectra `change` (forward_change), gives it: C_xx and C_yy real, C_xy = i·c_xy.
  void add(Index target, Index source, const Vector& change, Eigen::Ref<Vector> target_spectra) const {
    const Index f = frequencies_;
    const auto kernel = kernels_.col(rows_ - 1 + target - source);
    const auto xx = kernel.segment(0, f).array(), xy = kernel.segment(f, f).array(), yy = kernel.segment(2 * f, f).array();
    const auto x_re = change.segment(0, f).array(), x_im = change.segment(f, f).array();
    const auto y_re = change.segment(2 * f, f).array(), y_im = change.segment(3 * f, f).array();
    target_spectra.segment(0, f).array() += xx * x_re - xy * y_im;
    target_spectra.segment(f, f).array() += xx * x_im + xy * y_re;
    target_spectra.segment(2 * f, f).array() += yy * y_re - xy * x_im;
    target_spectra.segment(3 * f, f).array() += yy * y_im + xy * x_re;
  }

 private:
  Index first_column_, columns_, rows_, length_, frequencies_;
  Eigen::FFT<Scalar> fft_;
  Matrix kernels_;  // 3F × (2 rows − 1): column rows − 1 + dj holds Re C_xx, Im C_xy, Re C_yy of offset dj
  Vector difference_re_, difference_im_;  // D's factor per frequency
  Vector line_;
  std::vector<std::complex<Scalar>> spectrum_;
};

/// One element's traction under Coulomb's law when its slip is s = r + (k_x p_x, k_y p_y)
/// (docs/tangential.md §7): adhesion p = −r/k if that is within the bound g (s = 0), else
/// slip p = −g s/|s|, i.e. p_c = −g r_c/(σ + g k_c) with σ = |s| the root of
/// Σ_c r_c²/(σ + g k_c)² = 1, convex and decreasing in σ, so that Newton's method from below
/// the root climbs to it monotonically. It starts from σ₀ = |r| − Σ_c w_c g k_c, the weights
/// w_c = r_c²/|r|²: with d_c = (g k_c − Σ w g k)/|r|, which the weights average to zero, the
/// sum at σ₀ is Σ_c w_c/(1 + d_c)² ≥ 1 by Jensen's inequality (1/(1 + d)² is convex), so σ₀
/// lies below the root, and within about (3/2)|r|·Σ_c w_c d_c² of it. Newton's passes per
/// element in slip (the last finding no progress), three wheel–rail patches at three
/// creepage scales: 3.6 from σ₀, 4.9 from |r| − g·max k; σ = 0 took tens when |r| ≫ g k.
template <typename Scalar>
struct ElementTraction {
  Scalar x, y;
  TractionState state;
};

template <typename Scalar>
ElementTraction<Scalar> coulomb_element(Scalar rx, Scalar ry, Scalar bound, Scalar kx, Scalar ky) {
  const Scalar adhesion_x = -rx / kx, adhesion_y = -ry / ky;
  if (adhesion_x * adhesion_x + adhesion_y * adhesion_y <= bound * bound) {
    return {adhesion_x, adhesion_y, TractionState::adhesion};
  }
  const Scalar rx2 = rx * rx, ry2 = ry * ry, size_squared = rx2 + ry2;  // slips: no overflow
  Scalar sigma = std::max(Scalar(0), std::sqrt(size_squared) - bound * (rx2 * kx + ry2 * ky) / size_squared);
  for (int newton = 0; newton < 100; ++newton) {
    const Scalar ex = sigma + bound * kx, ey = sigma + bound * ky;
    const Scalar excess = rx2 / (ex * ex) + ry2 / (ey * ey) - 1;
    const Scalar derivative = -2 * (rx2 / (ex * ex * ex) + ry2 / (ey * ey * ey));
    const Scalar next = sigma - excess / derivative;
    if (!(next > sigma) || next - sigma <= std::numeric_limits<Scalar>::epsilon() * next) {
      sigma = std::max(sigma, next);
      break;
    }
    sigma = next;
  }
  return {-bound * rx / (sigma + bound * kx), -bound * ry / (sigma + bound * ky), TractionState::slip};
}

}  // namespace detail

/// Steady rolling with Coulomb friction on the patches of one grid: the solver keeps the
/// tangential influence table and the steady-rolling operator of its grid and rolling
/// direction (both h-independent), and solves for any normal solution on that grid.
///
/// Discretisation (docs/tangential.md §6): in each contact element I the slip is
/// s_I = w_I + Σ_J D_IJ p_J (Eq. (T6)), with the spin term of w_y evaluated a sixth of an
/// element towards the leading edge as CONTACT does; in adhesion s_I = 0 and
/// |p_I| ≤ μ p_n,I, in slip p_I = −μ p_n,I s_I/|s_I|. Each sweep solves every element's
/// 2 × 2 problem with the others fixed, from the leading edge to the trailing one, moving the
/// adhesion stretch behind the element with it; the row's own slips follow each change, the
/// other rows' follow the finished row's change through their spectra along x (nonlinear
/// Gauss–Seidel in the differences of Eq. (T7), Anderson-mixed once the adhesion and slip
/// areas hold, docs/tangential.md §7).
///
/// **Example**
/// @code
/// fastnorm::SteadyRollingSolver<> rolling(grid, material);
/// fastnorm::Creepage<> creepage;
/// creepage.longitudinal = 1e-3;
/// auto answer = rolling.solve(normal, 0.3, creepage);   // normal: NormSolver's solution on grid
/// double fx = answer.force_x;                            // N, on body 1
/// @endcode
template <typename Scalar = double>
class SteadyRollingSolver {
 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// @throws fastnorm::invalid_argument for invalid options
  SteadyRollingSolver(const Grid<Scalar>& grid, const Material<Scalar>& material,
                      RollingDirection direction = RollingDirection::positive_x, TangentialOptions<Scalar> options = {})
      : options_(validated(options)),
        direction_(direction),
        influence_(std::make_shared<const TangentialInfluenceTable<Scalar>>(grid, material)),
        rolling_(std::make_shared<const detail::RollingOperator<Scalar>>(*influence_, direction)) {}

  const Grid<Scalar>& grid() const { return influence_->grid(); }
  const TangentialInfluenceTable<Scalar>& influence() const { return *influence_; }
  RollingDirection direction() const { return direction_; }
  const TangentialOptions<Scalar>& options() const { return options_; }

  /// Steady rolling of the patch whose normal solution is `normal` (on this grid), with
  /// Coulomb friction `friction` (μ > 0) and the creepages `creepage`.
  /// @throws fastnorm::invalid_argument for a normal solution of another grid or without an
  ///         answer, a friction coefficient that is not positive and finite, non-finite
  ///         creepages, or a contact area that reaches the grid's upstream edge (the slip
  ///         there needs the displacement one element beyond it)
  TangentialSolution<Scalar> solve(const Solution<Scalar>& normal, Scalar friction,
                                   const Creepage<Scalar>& creepage) const {
    const Grid<Scalar>& grid = influence_->grid();
    const detail::RollingOperator<Scalar>& rolling = *rolling_;
    const Index mx = grid.mx(), my = grid.my(), n = grid.size();
    detail::check_tangential_input(grid, normal, friction, creepage, "SteadyRollingSolver::solve");
    const Index upstream = rolling.shift;  // towards the leading edge
    const Index upstream_column = upstream > 0 ? mx - 1 : 0;

    TangentialSolution<Scalar> answer = detail::zero_answer<Scalar>(n);
    Vector bound = Vector::Zero(n);  // μ p_n
    for (Index k = 0; k < n; ++k) {
      if (!detail::carries_pressure(normal, k)) continue;
      FASTNORM_CHECK(grid.i_of(k) != upstream_column,
                     "SteadyRollingSolver::solve: the contact area reaches the grid's upstream edge (column " +
                         std::to_string(upstream_column) + "); extend the grid by an element there");
      bound(k) = friction * normal.pressure(k);
      answer.state(k) = TractionState::adhesion;
    }
    const Scalar scale = bound.maxCoeff();
    if (!(scale > 0)) return detail::no_contact_answer<Scalar>(n);

    // The rigid slip (T5), its spin term shifted by a sixth of an element as CONTACT's.
    const Scalar spin_shift = detail::spin_shift(grid, direction_);
    Vector rigid_x(n), rigid_y(n);
    for (Index k = 0; k < n; ++k) {
      const Scalar x = grid.x(grid.i_of(k)), y = grid.y(grid.j_of(k));
      rigid_x(k) = creepage.longitudinal - creepage.spin * (y - creepage.spin_centre_y);
      rigid_y(k) = creepage.lateral + creepage.spin * (x + spin_shift - creepage.spin_centre_x);
    }

    // The rows of the grid that hold contact, and the columns each spans: only there is the
    // slip read (docs/tangential.md §7). The box they span bounds the rows' spectra.
    std::vector<Index> first_column(static_cast<std::size_t>(my), mx), last_column(static_cast<std::size_t>(my), -1);
    Index box_first_column = mx, box_last_column = -1, box_first_row = my, box_last_row = -1;
    for (Index k = 0; k < n; ++k) {
      if (answer.state(k) == TractionState::exterior) continue;
      const Index i = grid.i_of(k), j = grid.j_of(k);
      first_column[static_cast<std::size_t>(j)] = std::min(first_column[static_cast<std::size_t>(j)], i);
      last_column[static_cast<std::size_t>(j)] = std::max(last_column[static_cast<std::size_t>(j)], i);
      box_first_column = std::min(box_first_column, i), box_last_column = std::max(box_last_column, i);
      box_first_row = std::min(box_first_row, j), box_last_row = std::max(box_last_row, j);
    }
    const Index box_rows = box_last_row - box_first_row + 1;
    detail::RowSpectra<Scalar> spectra(rolling, box_first_column, box_last_column - box_first_column + 1, box_rows);
    const Index spectrum_size = spectra.spectrum_size();

    // The iterate: the tractions p and the spectra of the elastic slips D p of every box row
    // (T7), kept up to date as rows change. A sweep reads a row's D p back from its spectrum
    // when it reaches the row and keeps it up to date along the row: moving p by `change` on
    // a stretch of the row from column `from` down to the column before `to` changes q by
    // +change at `from` and −change at `to` (which may lie one column beyond the grid), which
    // moves the row's slips by the difference of two slices of the row's column of C (a
    // slice of D when the stretch is the element alone). Once the row is done, its change
    // goes to every row's spectrum: the rows ahead see it before the sweep reaches them, as
    // they would element by element.
    Vector iterate = Vector::Zero(2 * n + spectrum_size * box_rows);
    auto tractions = iterate.head(2 * n), traction_x = iterate.segment(0, n), traction_y = iterate.segment(n, n);
    auto elastic_spectrum = [&](Index j) { return iterate.segment(2 * n + spectrum_size * (j - box_first_row), spectrum_size); };
    Vector elastic_x = Vector::Zero(n), elastic_y = Vector::Zero(n), row_change(2 * mx), change_spectrum(spectrum_size);
    auto shift_stretch = [&](Index from, Index to, Index j, Scalar change_x, Scalar change_y) {
      for (Index moved = from; moved != to; moved -= upstream) {
        traction_x(moved + mx * j) += change_x;
        traction_y(moved + mx * j) += change_y;
      }
      const Index first = first_column[static_cast<std::size_t>(j)], length = last_column[static_cast<std::size_t>(j)] - first + 1;
      // C(i_t − from, 0) − C(i_t − to, 0) for i_t = first … last
      const Index at_from = mx + first - from, at_to = mx + first - to;
      auto target_x = elastic_x.segment(j * mx + first, length), target_y = elastic_y.segment(j * mx + first, length);
      const auto xx = rolling.xx.col(my - 1), xy = rolling.xy.col(my - 1), yy = rolling.yy.col(my - 1);
      const auto dxx = xx.segment(at_from, length) - xx.segment(at_to, length);
      const auto dxy = xy.segment(at_from, length) - xy.segment(at_to, length);
      const auto dyy = yy.segment(at_from, length) - yy.segment(at_to, length);
      target_x += change_x * dxx + change_y * dxy;
      target_y += change_x * dxy + change_y * dyy;
    };
    auto elastic_of_row = [&](Index j) { spectra.inverse(elastic_spectrum(j), elastic_x.data() + j * mx, elastic_y.data() + j * mx); };
    // row_change holds the row's tractions (x then y) before the sweep reached it.
    auto spread_row_change = [&](Index j) {
      row_change.head(mx) = traction_x.segment(j * mx, mx) - row_change.head(mx);
      row_change.tail(mx) = traction_y.segment(j * mx, mx) - row_change.tail(mx);
      if (row_change.cwiseAbs().maxCoeff() == 0) return;
      spectra.forward_change(row_change.data(), row_change.data() + mx, change_spectrum);
      for (Index target = box_first_row; target <= box_last_row; ++target) {
        if (last_column[static_cast<std::size_t>(target)] < 0) continue;
        spectra.add(target - box_first_row, j - box_first_row, change_spectrum, elastic_spectrum(target));
      }
    };

    // Each sweep visits the contact rows, each from the leading edge to the trailing one. At
    // an element it moves the traction of the element and of the adhesion stretch behind it
    // (down to the first element in slip or outside the contact, whose traction stays), so
    // that the element meets Coulomb's conditions with the rest fixed; the local coefficient
    // is the move's own, (C(0) − C(I − J))/dx with J the stretch's end, times a relaxation ρ
    // (docs/tangential.md §7).
    // Once a sweep leaves every element's state as it found it, the sweeps are Anderson-mixed
    // (tractions and spectra together: both are linear in p).
    // A sweep whose largest change grows tenfold past the smallest met, or a smallest change
    // that does not halve in 40 sweeps, restarts the solve from zero with ρ 1.5 times larger
    // (whichever rule stops the sweeps); the iterate it leaves is kept if its measure is the
    // least met, and returned if the sweeps end unconverged with none better.
    // A sweep relaxed by ρ moves the tractions by about 1/ρ of its unrelaxed step, so the
    // measure of its changes is taken times ρ/ρ₀: a restarted, more relaxed solve must not
    // stop merely because its steps are shorter.
    const Scalar own_x = rolling.xx(mx, my - 1), own_y = rolling.yy(mx, my - 1);
    const Scalar first_relaxation = Scalar(1.5);
    Scalar relaxation = first_relaxation;
    detail::AndersonMixing<Scalar> mixing(iterate.size(), 2 * n, 6);
    Vector before(2 * n), residual(2 * n);
    Scalar smallest_change = std::numeric_limits<Scalar>::infinity(), checkpoint_change = smallest_change;
    int checkpoint_sweep = 0;
    Vector kept_iterate;
    Eigen::Matrix<TractionState, Eigen::Dynamic, 1> kept_state;
    Scalar kept_residual = std::numeric_limits<Scalar>::infinity();
    answer.sweeps = 0;
    bool converged = false;
    while (answer.sweeps < options_.max_sweeps) {
      ++answer.sweeps;
      before = tractions;
      bool states_changed = false;
      for (Index j = 0; j < my; ++j) {
        if (last_column[static_cast<std::size_t>(j)] < 0) continue;
        elastic_of_row(j);
        row_change.head(mx) = traction_x.segment(j * mx, mx);
        row_change.tail(mx) = traction_y.segment(j * mx, mx);
        for (Index i = upstream_column; i >= 0 && i < mx; i -= upstream) {
          const Index k = i + mx * j;
          if (answer.state(k) == TractionState::exterior) continue;
          Index end = i - upstream;  // the first element behind that keeps its traction
          while (end >= 0 && end < mx && answer.state(end + mx * j) == TractionState::adhesion) end -= upstream;
          const Scalar local_x = relaxation * (own_x - rolling.xx(mx + i - end, my - 1));
          const Scalar local_y = relaxation * (own_y - rolling.yy(mx + i - end, my - 1));
          const Scalar px = traction_x(k), py = traction_y(k);
          const auto local = detail::coulomb_element(rigid_x(k) + elastic_x(k) - local_x * px,
                                                     rigid_y(k) + elastic_y(k) - local_y * py, bound(k), local_x, local_y);
          states_changed = states_changed || local.state != answer.state(k);
          answer.state(k) = local.state;
          if (local.x != px || local.y != py) shift_stretch(i, end, j, local.x - px, local.y - py);
        }
        spread_row_change(j);
      }
      residual = tractions - before;
      const Scalar largest_change = residual.cwiseAbs().maxCoeff();
      if (options_.stop == TangentialStop::largest_change) {
        answer.residual = largest_change / scale;
      } else {  // sums over the grid are sums over the contact: p is zero outside it
        // A sweep that leaves no traction answers a zero rigid slip exactly.
        const Scalar size = tractions.norm();
        answer.residual = size > 0 ? residual.norm() / size : Scalar(0);
      }
      answer.residual *= relaxation / first_relaxation;
      converged = answer.residual <= options_.tolerance;
      if (converged) break;
      smallest_change = std::min(smallest_change, largest_change);
      bool stagnating = false;
      if (answer.sweeps - checkpoint_sweep >= 40) {
        stagnating = smallest_change > checkpoint_change / 2;
        checkpoint_change = smallest_change;
        checkpoint_sweep = answer.sweeps;
      }
      if (stagnating || largest_change > 10 * smallest_change) {  // restart, more relaxed
        if (answer.residual < kept_residual) {
          kept_residual = answer.residual;
          kept_iterate = iterate;
          kept_state = answer.state;
        }
        relaxation *= Scalar(1.5);
        smallest_change = checkpoint_change = std::numeric_limits<Scalar>::infinity();
        checkpoint_sweep = answer.sweeps;
        iterate.setZero();
        for (Index k = 0; k < n; ++k) {
          if (answer.state(k) != TractionState::exterior) answer.state(k) = TractionState::adhesion;
        }
        mixing.reset();
      } else if (!states_changed) {
        mixing.mix(iterate, residual);
      } else {
        mixing.reset();
      }
    }
    if (!converged && kept_residual < answer.residual) {
      iterate = kept_iterate;
      answer.state = kept_state;
      answer.residual = kept_residual;
    }
    answer.traction_x = traction_x;
    answer.traction_y = traction_y;

    for (Index j = box_first_row; j <= box_last_row; ++j) {
      if (last_column[static_cast<std::size_t>(j)] >= 0) elastic_of_row(j);
    }
    for (Index k = 0; k < n; ++k) {
      if (answer.state(k) != TractionState::slip) continue;
      answer.slip_x(k) = rigid_x(k) + elastic_x(k);
      answer.slip_y(k) = rigid_y(k) + elastic_y(k);
    }
    detail::sum_tangential(grid, answer);
    if (!converged) {
      answer.status = Status::iteration_limit;
      answer.message = "tractions still changing after " + std::to_string(options_.max_sweeps) + " sweeps";
    } else {
      answer.status = Status::converged;
      answer.message = "tractions stable";
    }
    return answer;
  }

 private:
  static TangentialOptions<Scalar> validated(TangentialOptions<Scalar> options) {
    options.validate();
    return options;
  }

  TangentialOptions<Scalar> options_;
  RollingDirection direction_;
  std::shared_ptr<const TangentialInfluenceTable<Scalar>> influence_;
  std::shared_ptr<const detail::RollingOperator<Scalar>> rolling_;  // shared by copies
};

/// One steady-rolling solve (see SteadyRollingSolver): builds the solver's tables for
/// `grid` and `material`, which a loop over many solves on one grid should keep instead.
/// @throws fastnorm::invalid_argument as SteadyRollingSolver and its solve
template <typename Scalar>
TangentialSolution<Scalar> solve_steady_rolling(const Grid<Scalar>& grid, const Material<Scalar>& material,
                                                const Solution<Scalar>& normal, Scalar friction,
                                                const Creepage<Scalar>& creepage,
                                                RollingDirection direction = RollingDirection::positive_x,
                                                const TangentialOptions<Scalar>& options = {}) {
  return SteadyRollingSolver<Scalar>(grid, material, direction, options).solve(normal, friction, creepage);
}

}  // namespace fastnorm
