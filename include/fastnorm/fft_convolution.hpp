#pragma once
/// @file fft_convolution.hpp
/// The product u = C p over the whole grid as a zero-padded 2-D FFT convolution of the
/// Toeplitz kernel (docs/performance.md §2): O(N log N) time and O(N) memory, where the
/// direct product costs O(N²).

#include <unsupported/Eigen/FFT>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/influence.hpp"

namespace fastnorm {

namespace detail {

/// Smallest n ≥ minimum that is a multiple of `multiple_of` and has no prime factor above 5:
/// the lengths Eigen's FFT (kissfft) handles with its fast radices.
inline Eigen::Index smooth_fft_length(Eigen::Index minimum, Eigen::Index multiple_of) {
  for (Eigen::Index n = minimum;; ++n) {
    if (n % multiple_of != 0) continue;
    Eigen::Index rest = n;
    for (Eigen::Index factor : {2, 3, 5}) {
      while (rest % factor == 0) rest /= factor;
    }
    if (rest == 1) return n;
  }
}

/// Eigen's FFT without scaling (the callers fold 1/n into their kernels) and with half
/// spectra of real sequences (n/2 + 1 values).
template <typename Scalar>
Eigen::FFT<Scalar> half_spectrum_fft() {
  return Eigen::FFT<Scalar>(typename Eigen::FFT<Scalar>::impl_type(),
                            static_cast<typename Eigen::FFT<Scalar>::Flag>(Eigen::FFT<Scalar>::Unscaled |
                                                                          Eigen::FFT<Scalar>::HalfSpectrum));
}

}  // namespace detail

/// u = C p on a grid by FFT. The kernel offsets (di, dj), |di| < mx, |dj| < my, are laid
/// out circularly on an nx × ny grid with nx ≥ 2mx − 1, ny ≥ 2my − 1, so the circular
/// convolution of the zero-padded p equals the Toeplitz product on the grid. The kernel is
/// even in x and y, so its transform is real; it is computed once, with the 1/(nx·ny) of
/// the inverse transform folded in, and shared by copies.
///
/// Transforms: real-to-half-complex along x for the my rows that hold pressure, complex
/// along y for the nx/2 + 1 frequencies, and back. All workspace is allocated by the
/// constructor: `apply` does not allocate. An object is not safe to share between threads
/// (the FFT plans and workspace are its own); copy it instead: a copy has its own plans and
/// buffers and shares the kernel's transform.
///
/// **Example**
/// @code
/// fastnorm::InfluenceTable<> table(grid, steel);
/// fastnorm::FftConvolution<> convolution(table);
/// Eigen::VectorXd u(grid.size());
/// convolution.apply(pressure, u);   // u = C p (m), pressure in Pa
/// @endcode
template <typename Scalar = double>
class FftConvolution {
 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Complex = std::complex<Scalar>;

  explicit FftConvolution(const InfluenceTable<Scalar>& influence) : FftConvolution(influence, Kernel::toeplitz) {}

  /// CG's preconditioner K ≈ C⁻¹ (docs/performance.md §9): the inverse of the circulant
  /// matrix whose kernel is C at the nearest periodic image of every offset, on a period
  /// of about the grid's own size (nx ≥ mx, ny ≥ my). Its symbol is C's inverted: it grows
  /// as the wavenumber, as the inverse of the half-space operator does, and its kernel
  /// decays as 1/r³, so one grid's period is enough (the wrapped-around couplings are
  /// small) and its transforms cost a quarter of C's. `apply(w, z)` gives z = K w (Pa) for
  /// a gap w (m).
  static FftConvolution approximate_inverse(const InfluenceTable<Scalar>& influence) {
    return FftConvolution(influence, Kernel::periodic_inverse);
  }

  Index padded_x() const { return nx_; }
  /// True if `other` is a copy of this convolution (or this of it): the same kernel.
  bool same_kernel(const FftConvolution& other) const { return symbol_ == other.symbol_; }
  Index padded_y() const { return ny_; }

  /// u = C p: displacements (m) at every element due to the pressures p (Pa).
  /// @param pressure grid.size() values, element k = i + mx·j
  /// @param displacement grid.size() values, overwritten
  void apply(const Eigen::Ref<const Vector>& pressure, Eigen::Ref<Vector> displacement) {
    FASTNORM_CHECK(pressure.size() == mx_ * my_ && displacement.size() == mx_ * my_,
                   detail::describe("fft convolution: pressure and displacement must have grid.size() values",
                                    pressure.size()));
    for (Index j = 0; j < my_; ++j) {
      real_line_.head(mx_) = pressure.segment(j * mx_, mx_);
      real_line_.tail(nx_ - mx_).setZero();
      fft_.fwd(spectrum_.col(j).data(), real_line_.data(), nx_);
    }
    spectrum_.rightCols(ny_ - my_).setZero();
    for (Index kx = 0; kx < half_; ++kx) {
      forward_along_y(kx);
      for (Index ky = 0; ky < ny_; ++ky) line_spectrum_[static_cast<std::size_t>(ky)] *= (*symbol_)(kx, ky);
      fft_.inv(line_.data(), line_spectrum_.data(), ny_);
      for (Index j = 0; j < my_; ++j) spectrum_(kx, j) = line_[static_cast<std::size_t>(j)];  // rows ≥ my unused
    }
    for (Index j = 0; j < my_; ++j) {
      fft_.inv(real_line_.data(), spectrum_.col(j).data(), nx_);
      displacement.segment(j * mx_, mx_) = real_line_.head(mx_);
    }
  }

 private:
  enum class Kernel { toeplitz, periodic_inverse };

  FftConvolution(const InfluenceTable<Scalar>& influence, Kernel kernel)
      : mx_(influence.grid().mx()),
        my_(influence.grid().my()),
        // Zero-padded to 2m − 1 or periodic over m; nx a multiple of 4 (kissfft's fast real
        // path), ny ≥ 2 (kissfft's least length).
        nx_(detail::smooth_fft_length(kernel == Kernel::toeplitz ? 2 * mx_ : mx_, 4)),
        ny_(detail::smooth_fft_length(std::max<Index>(kernel == Kernel::toeplitz ? 2 * my_ - 1 : my_, 2), 1)),
        half_(nx_ / 2 + 1),
        fft_(detail::half_spectrum_fft<Scalar>()),
        spectrum_(half_, ny_),
        line_(static_cast<std::size_t>(ny_)),
        line_spectrum_(static_cast<std::size_t>(ny_)),
        real_line_(nx_) {
    const Grid<Scalar>& grid = influence.grid();
    // C at offset (di, dj), beyond the table by Love's formula.
    auto coefficient = [&](Index di, Index dj) {
      if (std::abs(di) < mx_ && std::abs(dj) < my_) return influence.at_offset(di, dj);
      return love_coefficient<Scalar>(static_cast<Scalar>(di) * grid.dx(), static_cast<Scalar>(dj) * grid.dy(),
                                      grid.dx() / 2, grid.dy() / 2, influence.combined_modulus());
    };
    // The kernel on the circular nx × ny grid: offset d sits at d mod n. Zero-padded, the
    // circular convolution equals the Toeplitz product on the grid; periodic, every entry
    // holds its offset's nearest image.
    const bool padded = kernel == Kernel::toeplitz;
    auto offset = [&](Index index, Index n, Index m) { return index < (padded ? m : n / 2 + 1) ? index : index - n; };
    Vector row(nx_);
    for (Index j = 0; j < ny_; ++j) {
      const Index dj = offset(j, ny_, my_);
      for (Index i = 0; i < nx_; ++i) {
        const Index di = offset(i, nx_, mx_);
        row(i) = padded && (di <= -mx_ || dj <= -my_) ? Scalar(0) : coefficient(di, dj);
      }
      fft_.fwd(spectrum_.col(j).data(), row.data(), nx_);
    }
    auto symbol = std::make_shared<RealMatrix>(half_, ny_);
    for (Index kx = 0; kx < half_; ++kx) {
      forward_along_y(kx);
      // Even kernel: the imaginary parts are round-off; keep the real part.
      for (Index ky = 0; ky < ny_; ++ky) (*symbol)(kx, ky) = line_spectrum_[static_cast<std::size_t>(ky)].real();
    }
    if (kernel == Kernel::periodic_inverse) {
      // C's periodic symbol is positive on every grid tried (its smallest value is about
      // 1/n of its largest); a floor keeps K positive definite whatever the grid.
      const Scalar floor = symbol->maxCoeff() * std::sqrt(std::numeric_limits<Scalar>::epsilon());
      *symbol = symbol->cwiseMax(floor).cwiseInverse();
    }
    *symbol /= static_cast<Scalar>(nx_ * ny_);  // the unscaled inverse transform's factor
    symbol_ = std::move(symbol);
    // One product creates the inverse plans and buffers, so that apply() never allocates.
    Vector zero = Vector::Zero(mx_ * my_);
    apply(zero, zero);
  }

  /// Row kx of spectrum_ transformed along y into line_spectrum_.
  void forward_along_y(Index kx) {
    for (Index ky = 0; ky < ny_; ++ky) line_[static_cast<std::size_t>(ky)] = spectrum_(kx, ky);
    fft_.fwd(line_spectrum_.data(), line_.data(), ny_);
  }

  Index mx_, my_, nx_, ny_, half_;
  Eigen::FFT<Scalar> fft_;
  using RealMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  std::shared_ptr<const RealMatrix> symbol_;  // half_ × ny_, real kernel spectrum / (nx·ny)
  Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic> spectrum_;  // half_ × ny_ work array
  std::vector<Complex> line_, line_spectrum_;
  Vector real_line_;
};

}  // namespace fastnorm
