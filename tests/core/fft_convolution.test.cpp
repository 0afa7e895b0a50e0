// The FFT product C p against the direct Toeplitz sum of InfluenceTable::displacement.
#include <catch2/catch.hpp>
#include <fastnorm/fft_convolution.hpp>

using Catch::Matchers::Contains;

namespace {

template <typename Scalar>
double fft_versus_direct(Eigen::Index mx, Eigen::Index my) {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const fastnorm::Grid<Scalar> grid(mx, my, Scalar(3e-4), Scalar(4.4e-4), Scalar(-1e-3), Scalar(2e-3));
  const fastnorm::InfluenceTable<Scalar> table(grid, fastnorm::Material<Scalar>(Scalar(2.1e11), Scalar(0.3)));
  fastnorm::FftConvolution<Scalar> convolution(table);
  // Pressures of both signs and a zero row, so that no symmetry hides an indexing error.
  Vector pressure = Vector::Random(grid.size()) * Scalar(1e9);
  if (my > 1) pressure.segment(0, mx).setZero();
  Vector fast(grid.size());
  convolution.apply(pressure, fast);
  const Vector direct = table.displacement(pressure);
  return static_cast<double>((fast - direct).cwiseAbs().maxCoeff() / direct.cwiseAbs().maxCoeff());
}

}  // namespace

TEST_CASE("FFT convolution equals the direct product C p", "[core][fft]") {
  for (auto size : {std::pair<Eigen::Index, Eigen::Index>{1, 1}, {1, 9}, {9, 1}, {7, 5}, {59, 61}, {61, 58}}) {
    INFO(size.first << " x " << size.second);
    CHECK(fft_versus_direct<double>(size.first, size.second) < 1e-13);
  }
  CHECK(fft_versus_direct<float>(30, 31) < 1e-5);
}

TEST_CASE("FFT convolution pads to lengths with factors 2, 3 and 5 only", "[core][fft]") {
  CHECK(fastnorm::detail::smooth_fft_length(118, 4) == 120);
  CHECK(fastnorm::detail::smooth_fft_length(121, 1) == 125);
  CHECK(fastnorm::detail::smooth_fft_length(961, 4) == 972);
  const fastnorm::Grid<> grid(59, 61, 1e-4, 1e-4);
  const fastnorm::FftConvolution<> convolution(fastnorm::InfluenceTable<>(grid, fastnorm::Material<>(2.1e11, 0.3)));
  CHECK(convolution.padded_x() == 120);
  CHECK(convolution.padded_y() == 125);
}

TEST_CASE("FFT convolution rejects vectors of the wrong size", "[core][fft]") {
  const fastnorm::Grid<> grid(4, 3, 1e-4, 1e-4);
  fastnorm::FftConvolution<> convolution(fastnorm::InfluenceTable<>(grid, fastnorm::Material<>(2.1e11, 0.3)));
  Eigen::VectorXd u(grid.size());
  CHECK_THROWS_WITH(convolution.apply(Eigen::VectorXd::Zero(5), u), Contains("pressure and displacement"));
}
