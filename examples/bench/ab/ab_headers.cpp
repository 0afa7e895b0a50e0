// ab_headers: two versions of fastnorm's headers timed in one process (built and run by
// ab.sh; docs/performance.md §1). The machine's speed drifts by 10-50 % over minutes and
// between processes, more than most changes measured; stepping both versions' models
// alternately, 50 steps at a time, in one process lets both meet the same machine, and
// their ratio is good to about 1 % (the A/A spread; ab.sh --same).
//
//   ab_headers [steps] [solver] [rounds] [pose_cache]
//
// Per round, one line:
//
//   round=<r> a_search_us= a_h_us= a_solve_us= a_total_us= b_…= solve_ratio=<b/a>
//     total_ratio=<b/a> max_force_difference=<largest |F_b/F_a - 1| of a wheel and step>
//
// then the medians of the rounds' ratios. Poses are cached in pose_cache (computing them
// takes seconds).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

extern "C" {
void ab_trajectory_a(int steps, std::vector<double>* flat);
void* ab_create_a(const double* flat, std::size_t steps, const char* solver);
void* ab_create_b(const double* flat, std::size_t steps, const char* solver);
void ab_run_a(void* model, std::size_t first, std::size_t end);
void ab_run_b(void* model, std::size_t first, std::size_t end);
void ab_finish_a(void* model, double* medians, std::vector<double>* forces);
void ab_finish_b(void* model, double* medians, std::vector<double>* forces);
}

namespace {

constexpr std::size_t values_per_step = 10;
constexpr std::size_t block = 50;  // steps of one model before the other's

std::vector<double> trajectory(int steps, const std::string& cache) {
  std::vector<double> flat(values_per_step * static_cast<std::size_t>(steps));
  if (FILE* file = std::fopen(cache.c_str(), "rb")) {
    const bool complete = std::fread(flat.data(), sizeof(double), flat.size(), file) == flat.size();
    std::fclose(file);
    if (complete) return flat;
  }
  flat.clear();
  ab_trajectory_a(steps, &flat);
  if (FILE* file = std::fopen(cache.c_str(), "wb")) {
    std::fwrite(flat.data(), sizeof(double), flat.size(), file);
    std::fclose(file);
  }
  return flat;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 2000;
  const char* solver = argc > 2 ? argv[2] : "elliptic";
  const int rounds = argc > 3 ? std::atoi(argv[3]) : 3;
  const std::string cache = argc > 4 ? argv[4] : "ab_poses_" + std::to_string(steps) + ".bin";
  if (steps < 1 || rounds < 1) {
    std::fprintf(stderr, "ab_headers: steps and rounds must be positive\n");
    return 2;
  }
  const std::vector<double> flat = trajectory(steps, cache);
  const auto n = static_cast<std::size_t>(steps);
  std::vector<double> solve_ratios, total_ratios;
  for (int round = 0; round < rounds; ++round) {
    void* a = ab_create_a(flat.data(), n, solver);
    void* b = ab_create_b(flat.data(), n, solver);
    for (std::size_t first = 0; first < n; first += block) {
      const std::size_t end = std::min(first + block, n);
      // Which goes first alternates by block and round.
      if ((first / block + static_cast<std::size_t>(round)) % 2 == 0) {
        ab_run_a(a, first, end), ab_run_b(b, first, end);
      } else {
        ab_run_b(b, first, end), ab_run_a(a, first, end);
      }
    }
    double medians_a[4], medians_b[4];
    std::vector<double> forces_a, forces_b;
    ab_finish_a(a, medians_a, &forces_a);
    ab_finish_b(b, medians_b, &forces_b);
    double force_difference = 0;
    for (std::size_t k = 0; k < forces_a.size(); ++k) {
      if (forces_a[k] != 0) force_difference = std::max(force_difference, std::abs(forces_b[k] / forces_a[k] - 1));
    }
    solve_ratios.push_back(medians_b[2] / medians_a[2]);
    total_ratios.push_back(medians_b[3] / medians_a[3]);
    std::printf(
        "round=%d a_search_us=%.1f a_h_us=%.1f a_solve_us=%.1f a_total_us=%.1f b_search_us=%.1f b_h_us=%.1f "
        "b_solve_us=%.1f b_total_us=%.1f solve_ratio=%.3f total_ratio=%.3f max_force_difference=%.2e\n",
        round, 1e6 * medians_a[0], 1e6 * medians_a[1], 1e6 * medians_a[2], 1e6 * medians_a[3], 1e6 * medians_b[0],
        1e6 * medians_b[1], 1e6 * medians_b[2], 1e6 * medians_b[3], solve_ratios.back(), total_ratios.back(),
        force_difference);
    std::fflush(stdout);
  }
  std::printf("ab solver=%s steps=%d rounds=%d solve_ratio_median=%.3f total_ratio_median=%.3f\n", solver, steps, rounds,
              median(solve_ratios), median(total_ratios));
  return 0;
}
