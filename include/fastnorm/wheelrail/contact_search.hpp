#pragma once
/// @file contact_search.hpp
/// Rigid contact search along the contact locus: the vertical gap between each wheel and
/// its rail, its local minima, and the interpenetration regions that become contact patches
/// (docs/wheel-rail.md §4).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/wheelrail/track.hpp"
#include "fastnorm/wheelrail/wheelset.hpp"

namespace fastnorm::wheelrail {

/// How the contact search samples the locus and groups what it finds (m, rad).
struct SearchOptions {
  double step = 0.05e-3;               ///< sampling of the wheel profile coordinate y_w
  double separation_distance = 8e-3;   ///< regions farther apart (rail points) stay separate patches
  double separation_angle = 0.5;       ///< ... as do regions whose mean inclinations differ by more
  double roll_bracket = 0.02;          ///< rigid_contact_pose seeks the roll within ±this (rad)
  double roll_tolerance = 1e-13;       ///< ... to this width of its bracket (rad)
  int max_root_steps = 200;            ///< most steps of that search

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    using fastnorm::detail::check_positive;
    check_positive(step, "SearchOptions: step (m)");
    check_positive(separation_distance, "SearchOptions: separation_distance (m)");
    check_positive(separation_angle, "SearchOptions: separation_angle (rad)");
    check_positive(roll_bracket, "SearchOptions: roll_bracket (rad)");
    check_positive(roll_tolerance, "SearchOptions: roll_tolerance (rad)");
    FASTNORM_CHECK(max_root_steps >= 1,
                   fastnorm::detail::describe("SearchOptions: max_root_steps must be >= 1", max_root_steps));
  }
};

/// The gap at one locus point.
struct GapSample {
  Wheelset::LocusPoint wheel;  ///< the wheel point on the locus
  double rail_z = 0;           ///< rail height below it (m, down)
  double rail_slope = 0;       ///< dZ/dy of the rail there
  double gap = std::numeric_limits<double>::infinity();  ///< Z_rail − z_wheel (m, > 0 separated); ∞ off the rail
};

/// An interpenetration region of one wheel: consecutive locus samples with gap < 0, plus
/// its penetration-weighted centre and inclination (the contact reference of its patch).
struct ContactRegion {
  Side side = Side::right;
  std::vector<GapSample> slices;  ///< the penetrating samples, by increasing y_w
  GapSample deepest;              ///< the sample of largest interpenetration
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< weighted centre on the rail (track frame, m)
  double inclination = 0;         ///< weighted mean rail inclination δ = atan(dZ/dy) (rad)
  double profile_y = 0;           ///< weighted mean wheel profile coordinate y_w (m)
  double weight = 0;              ///< total weight (for merging)
};

namespace detail {

/// The gap at the locus point `wheel`, the rail's height below it from
/// `rail_height(y_track)` → std::optional<ProfileValue<double>>.
template <typename RailHeight>
GapSample gap_below(const Wheelset::LocusPoint& wheel, const RailHeight& rail_height) {
  GapSample sample;
  sample.wheel = wheel;
  if (const auto rail = rail_height(wheel.point.y())) {
    sample.rail_z = rail->value;
    sample.rail_slope = rail->slope;
    sample.gap = rail->value - wheel.point.z();
  }
  return sample;
}

}  // namespace detail

/// The gap between `side`'s wheel and rail at wheel profile coordinate y_w, with the pose's
/// rotation and tan ψ given. `rail_y` may hold the rail profile coordinate of a nearby
/// sample to start from (Track::rail_height) and receives this one's.
inline GapSample gap_at(const Track& track, const Wheelset& wheelset, Side side, double profile_y,
                        const WheelsetPose& pose, const Eigen::Matrix3d& rotation, double tan_yaw, double& rail_y) {
  return detail::gap_below(wheelset.locus(side, profile_y, pose, rotation, tan_yaw),
                           [&](double y) { return track.rail_height(side, y, rail_y); });
}

/// The same, from no nearby sample.
inline GapSample gap_at(const Track& track, const Wheelset& wheelset, Side side, double profile_y,
                        const WheelsetPose& pose, const Eigen::Matrix3d& rotation) {
  double rail_y = std::numeric_limits<double>::quiet_NaN();
  return gap_at(track, wheelset, side, profile_y, pose, rotation, std::tan(pose.yaw), rail_y);
}

namespace detail {

/// The locus samples over a profile: y_w = y_min + k·step for k = 0 … last_sample (the last
/// clipped to y_max).
inline std::size_t last_sample(const ProfileCurve& profile, double step) {
  return static_cast<std::size_t>(std::ceil((profile.y_max() - profile.y_min()) / step));
}
inline double sample_y(const ProfileCurve& profile, double step, std::size_t k) {
  return std::min(profile.y_max(), profile.y_min() + static_cast<double>(k) * step);
}

}  // namespace detail

/// The gap sampled every `options.step` over the wheel profile.
inline std::vector<GapSample> sample_gap(const Track& track, const Wheelset& wheelset, Side side,
                                         const WheelsetPose& pose, const SearchOptions& options = {}) {
  check_pose(pose, "contact search");
  options.validate();
  const auto& profile = wheelset.profile();
  const auto count = detail::last_sample(profile, options.step);
  const Eigen::Matrix3d rotation = Wheelset::rotation(pose);
  std::vector<GapSample> samples;
  samples.reserve(count + 1);
  for (std::size_t k = 0; k <= count; ++k) {
    samples.push_back(gap_at(track, wheelset, side, detail::sample_y(profile, options.step, k), pose, rotation));
  }
  return samples;
}

/// What sample_gap gives where the gap may be negative, at a small part of its cost, for
/// one pose after another (docs/wheel-rail.md §4, item 3). Every `coarse_stride`-th sample
/// is taken first, then every sample between two coarse ones of which one lies below
/// `candidate_gap`; the samples not taken keep gap = +∞. Between coarse samples Δ = 0.5 mm
/// apart the gap dips below its chord by at most κΔ²/8 (κ its curvature), 3 µm even at a
/// 10 mm flange radius, far less than candidate_gap: every sample with gap < 0, and so every
/// contact region, is exactly the full sampling's (tests/wheelrail/geometry.test.cpp
/// compares the two on many poses).
///
/// From call to call (a time loop) a coarse sample is taken again only when the pose change
/// since it was taken could have brought its gap below candidate_gap: its locus point moves
/// by at most δ = |Δy| + |Δz| + (|Δroll| + |Δyaw|)·|q| + ρ·|Δθ| (q the point in wheelset
/// axes, θ its wheel angle), so its gap by at most (1 + S)·δ while δ ≤ `drift_limit`, S the
/// largest rail slope within drift_limit of its rail point; a point more than drift_limit
/// beyond the rail stays beyond it. A change of side, step, track or wheelset, or a pose
/// change beyond drift_limit, takes every coarse sample again.
class GapSampler {
 public:
  GapSampler() = default;
  GapSampler(const GapSampler& other) { *this = other; }
  /// A copy takes the other's samples where it took them (its refined stretches and coarse
  /// samples; every other sample is +∞ in both), not all of the thousands: a time loop's
  /// trial steps copy the search often (WheelsetContact::restore).
  GapSampler& operator=(const GapSampler& other) {
    if (this == &other) return *this;
    if (samples_.size() == other.samples_.size()) {
      for_taken([&](std::size_t k) { samples_[k] = GapSample{}; });
      other.for_taken([&](std::size_t k) { samples_[k] = other.samples_[k]; });
    } else {
      samples_ = other.samples_;
    }
    // Every other member as it is (a member added to the class is added here).
    track_id_ = other.track_id_, wheelset_id_ = other.wheelset_id_;
    rail_first_y_ = other.rail_first_y_, rail_last_y_ = other.rail_last_y_;
    side_ = other.side_, step_ = other.step_;
    last_pose_ = other.last_pose_;
    refined_ = other.refined_;
    coarse_ = other.coarse_;
    slope_bins_ = other.slope_bins_;
    return *this;
  }
  GapSampler(GapSampler&&) noexcept = default;
  GapSampler& operator=(GapSampler&&) noexcept = default;
  ~GapSampler() = default;

  /// The samples of `side` at `pose` (all 1 + ⌈(y_max − y_min)/step⌉ of them; storage
  /// reused from call to call).
  const std::vector<GapSample>& sample(const Track& track, const Wheelset& wheelset, Side side,
                                       const WheelsetPose& pose, const SearchOptions& options) {
    check_pose(pose, "contact search");
    options.validate();
    const auto& profile = wheelset.profile();
    const auto count = detail::last_sample(profile, options.step);
    const Eigen::Matrix3d rotation = Wheelset::rotation(pose);
    // The rail profile coordinates of the last two samples taken in a run of neighbours: the
    // next one's is extrapolated linearly from them (NaN: unknown, found by bracketing).
    double rail_y = std::numeric_limits<double>::quiet_NaN(), rail_y_before = rail_y;
    const double tan_yaw = std::tan(pose.yaw);
    auto take = [&](std::size_t k) {
      double guess = std::isfinite(rail_y_before) ? 2 * rail_y - rail_y_before : rail_y;
      samples_[k] = detail::gap_below(
          wheelset.locus(side, detail::sample_y(profile, options.step, k), pose, rotation, tan_yaw),
          [&](double y) { return track.rail_height_tabulated(side, y, guess); });
      rail_y_before = rail_y;
      rail_y = guess;
    };
    const bool continued = last_pose_ && track_id_ == track.id() && wheelset_id_ == wheelset.id() && side_ == side &&
                           step_ == options.step;
    if (!continued) start(track, wheelset, side, options.step, count);
    const WheelsetPose last = continued ? *last_pose_ : pose;
    last_pose_ = pose;
    // δ of §4 item 3 for a coarse sample c: the part common to every sample, then its own.
    const double shift = std::abs(pose.y - last.y) + std::abs(pose.z - last.z);
    const double turn = std::abs(pose.roll - last.roll) + std::abs(pose.yaw - last.yaw);
    const double tan_last = std::tan(last.yaw), tan_now = tan_yaw;
    const double tan_largest = std::max(std::abs(tan_last), std::abs(tan_now));
    auto drift_of = [&](const Coarse& c) {
      const double sine = std::abs(c.radius_slope) * tan_largest;  // |sin θ| at either pose
      if (!(sine < 0.9)) return std::numeric_limits<double>::infinity();
      const double angle_change = std::abs(c.radius_slope) * std::abs(tan_now - tan_last) / std::sqrt(1 - sine * sine);
      return shift + turn * c.reach + c.radius * angle_change;
    };
    // Back to +∞ only what the last call can have taken, its refined stretches and the
    // coarse samples: a few hundred of the thousands.
    if (samples_.size() == count + 1) {
      for_taken([&](std::size_t k) { samples_[k] = GapSample{}; });
    } else {
      samples_.assign(count + 1, GapSample{});
    }
    refined_.clear();
    for (std::size_t c = 0; c < coarse_.size(); ++c) {
      Coarse& coarse = coarse_[c];
      const std::size_t k = std::min(c * coarse_stride, count);
      coarse.drift += continued ? drift_of(coarse) : std::numeric_limits<double>::infinity();
      const bool still_far = coarse.drift <= drift_limit &&
                             (std::isfinite(coarse.gap)
                                  ? coarse.gap - (1 + coarse.slope_bound) * coarse.drift >= candidate_gap
                                  : coarse.beyond_rail > drift_limit);
      if (still_far) continue;  // its gap is still ≥ candidate_gap (or it is still off the rail)
      take(k);
      remember(samples_[k], wheelset, coarse);
    }
    for (std::size_t first = 0; first < count; first += coarse_stride) {
      const std::size_t last_k = std::min(first + coarse_stride, count);
      if (!(std::min(samples_[first].gap, samples_[last_k].gap) < candidate_gap)) continue;
      if (!refined_.empty() && refined_.back().second == first) {
        refined_.back().second = last_k;
      } else {
        refined_.emplace_back(first, last_k);
      }
      rail_y = rail_y_before = std::numeric_limits<double>::quiet_NaN();
      for (std::size_t k = first + 1; k < last_k; ++k) take(k);  // each from its neighbours' rail points
    }
    return samples_;
  }

  /// The next call takes every coarse sample.
  void reset() { last_pose_.reset(); }

  /// The stretches [first, last] of samples the last call took every sample of, by
  /// increasing y_w and apart from each other. Every sample with gap < candidate_gap, and so
  /// every penetrating one, lies in one: a coarse one is the end of the stretches on both its
  /// sides, the others are taken only inside them.
  const std::vector<std::pair<std::size_t, std::size_t>>& refined() const { return refined_; }

  /// Every coarse_stride-th sample is taken first.
  static constexpr std::size_t coarse_stride = 10;
  /// Samples between coarse ones are taken where one of those lies below this (m).
  static constexpr double candidate_gap = 0.05e-3;
  /// The largest drift δ (m) of a locus point over which a coarse sample is kept.
  static constexpr double drift_limit = 0.5e-3;

 private:
  /// A coarse sample as last taken, with what bounds its change.
  struct Coarse {
    double gap = 0;            ///< when taken (m; +∞ off the rail)
    double drift = 0;          ///< bound on its locus point's motion since (m)
    double slope_bound = 0;    ///< largest |rail slope| within drift_limit of its rail point
    double beyond_rail = 0;    ///< off the rail: how far beyond the rail's span (m)
    double radius = 0;         ///< ρ(y_w)
    double radius_slope = 0;   ///< dρ/dy_ws
    double reach = 0;          ///< |q|, the point's distance from the wheelset centre
  };

  /// `visit(k)` for every sample the last call can have taken: its refined stretches and the
  /// coarse samples (some twice).
  template <typename Visit>
  void for_taken(const Visit& visit) const {
    if (samples_.empty()) return;
    const std::size_t last = samples_.size() - 1;
    for (const auto& stretch : refined_) {
      for (std::size_t k = stretch.first; k <= stretch.second; ++k) visit(k);
    }
    for (std::size_t c = 0; c < coarse_.size(); ++c) visit(std::min(c * coarse_stride, last));
  }

  /// A cold start: every coarse sample to be taken, the slope table of a new track.
  void start(const Track& track, const Wheelset& wheelset, Side side, double step, std::size_t count) {
    if (track_id_ != track.id()) build_slope_bins(track);
    track_id_ = track.id(), wheelset_id_ = wheelset.id(), side_ = side, step_ = step;
    coarse_.assign(count / coarse_stride + 1 + (count % coarse_stride != 0), Coarse{});
  }

  void remember(const GapSample& sample, const Wheelset& wheelset, Coarse& coarse) const {
    coarse.gap = sample.gap;
    coarse.drift = 0;
    coarse.radius = sample.wheel.radius;
    coarse.radius_slope = sample.wheel.radius_slope;
    coarse.reach = std::hypot(sample.wheel.radius, wheelset.axle_coordinate(side_, sample.wheel.profile_y));
    const double y = side_sign(side_) * sample.wheel.point.y();  // on the right rail
    coarse.beyond_rail = std::max(rail_first_y_ - y, y - rail_last_y_);
    coarse.slope_bound = std::isfinite(sample.gap) ? slope_near(y) : 0;
  }

  /// The largest |slope| of the right rail within drift_limit of y: bins of width
  /// drift_limit, each with the largest |slope| of 41 points across it, raised by a quarter
  /// for what lies between them (the rail is a smooth spline), then the bin and its neighbours.
  void build_slope_bins(const Track& track) {
    const auto [first_y, last_y] = track.right_rail_span();
    rail_first_y_ = first_y, rail_last_y_ = last_y;
    const auto bins = static_cast<std::size_t>(std::ceil((last_y - first_y) / drift_limit));
    slope_bins_.assign(bins, 0);
    for (std::size_t b = 0; b < bins; ++b) {
      for (int k = 0; k <= 40; ++k) {
        const double y = std::min(last_y, first_y + (static_cast<double>(b) + k / 40.0) * drift_limit);
        if (const auto rail = track.rail_height(Side::right, y)) {
          slope_bins_[b] = std::max(slope_bins_[b], 1.25 * std::abs(rail->slope));
        }
      }
    }
  }

  double slope_near(double y) const {
    const auto bin = static_cast<std::ptrdiff_t>(std::floor((y - rail_first_y_) / drift_limit));
    double bound = 0;
    for (std::ptrdiff_t b = bin - 1; b <= bin + 1; ++b) {
      if (b >= 0 && b < static_cast<std::ptrdiff_t>(slope_bins_.size())) {
        bound = std::max(bound, slope_bins_[static_cast<std::size_t>(b)]);
      }
    }
    return bound;
  }

  // Whose samples these are: Track::id() and Wheelset::id() (0: none yet).
  std::uint64_t track_id_ = 0, wheelset_id_ = 0;
  double rail_first_y_ = 0, rail_last_y_ = 0;  // the right rail's span of the slope table (m)
  Side side_ = Side::right;
  double step_ = 0;
  std::optional<WheelsetPose> last_pose_;
  std::vector<GapSample> samples_;
  std::vector<std::pair<std::size_t, std::size_t>> refined_;
  std::vector<Coarse> coarse_;
  std::vector<double> slope_bins_;  // largest |slope| per drift_limit of the right rail
};

/// The samples of GapSampler for one pose.
inline std::vector<GapSample> sample_gap_near_contact(const Track& track, const Wheelset& wheelset, Side side,
                                                      const WheelsetPose& pose, const SearchOptions& options = {}) {
  GapSampler sampler;
  return sampler.sample(track, wheelset, side, pose, options);
}

/// Local minima of the gap (tread, flange root, flange …), each refined to 1e-9 m in y_w
/// by golden-section search between its sampled neighbours; by increasing y_w.
inline std::vector<GapSample> gap_minima(const Track& track, const Wheelset& wheelset, Side side,
                                         const WheelsetPose& pose, const SearchOptions& options = {}) {
  const auto samples = sample_gap(track, wheelset, side, pose, options);
  const Eigen::Matrix3d rotation = Wheelset::rotation(pose);
  std::vector<GapSample> minima;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double here = samples[k].gap;
    if (!std::isfinite(here)) continue;
    const double before = k > 0 ? samples[k - 1].gap : std::numeric_limits<double>::infinity();
    const double after = k + 1 < samples.size() ? samples[k + 1].gap : std::numeric_limits<double>::infinity();
    if (!(here <= before && here < after)) continue;
    const double low = samples[k > 0 ? k - 1 : k].wheel.profile_y;
    const double high = samples[k + 1 < samples.size() ? k + 1 : k].wheel.profile_y;
    const auto best = detail::golden_minimum(
        [&](double y_w) { return gap_at(track, wheelset, side, y_w, pose, rotation).gap; }, low, high, 1e-9);
    minima.push_back(gap_at(track, wheelset, side, best.first, pose, rotation));
  }
  return minima;
}

/// The smallest gap of `side` (m): how far the wheelset may drop before that wheel touches.
/// @throws fastnorm::invalid_argument if the wheel is nowhere above its rail
inline GapSample smallest_gap(const Track& track, const Wheelset& wheelset, Side side, const WheelsetPose& pose,
                              const SearchOptions& options = {}) {
  const auto minima = gap_minima(track, wheelset, side, pose, options);
  FASTNORM_CHECK(!minima.empty(), std::string("contact search: the ") + to_string(side) +
                                      " wheel is nowhere above its rail (lateral shift too large?)");
  return *std::min_element(minima.begin(), minima.end(),
                           [](const GapSample& a, const GapSample& b) { return a.gap < b.gap; });
}

/// The interpenetration regions of `side` at `pose`, merged as CONTACT does: neighbours
/// whose rail points lie closer than `separation_distance` and whose inclinations differ by
/// less than `separation_angle` form one patch. The centre, inclination and profile
/// coordinate are interpenetration-weighted means per unit of lateral track length, as
/// CONTACT's: a slice weighs ∫(−g(x))² dx over its overlap, g(x) = g − x²/(2ρ), i.e.
/// (16/15)·pen²·√(2ρ·pen), times the lateral track length it stands for (half the distance
/// in y_track between its neighbours), which at large yaw is not proportional to the
/// profile step (docs/wheel-rail.md §4, item 4).
///
/// Into the first regions of `regions`, by increasing y_w, from the samples of `sampler`
/// (which continues from its previous call); returns how many. The regions after those are
/// spares: `regions` never shrinks, so that it and its regions' slices keep their storage
/// from call to call, also when the patch count drops, and a time loop's search stops
/// allocating. A region's slices are given room for all the sampler's samples when the
/// region is first used (about 200 KB with the default step), so that no later call, however
/// long its regions, grows them: a search allocates only when it meets more regions than any
/// call before it.
inline std::size_t contact_regions(const Track& track, const Wheelset& wheelset, Side side, const WheelsetPose& pose,
                                   const SearchOptions& options, GapSampler& sampler,
                                   std::vector<ContactRegion>& regions) {
  const std::vector<GapSample>& samples = sampler.sample(track, wheelset, side, pose, options);
  std::size_t count = 0;  // regions in use; the others keep their storage until the end
  for (const auto& [first, last] : sampler.refined()) {  // the penetrating samples lie in these
    for (std::size_t k = first; k <= last; ++k) {
      if (!(samples[k].gap < 0)) continue;
      if (k == first || !(samples[k - 1].gap < 0)) {  // the sample before a stretch is not penetrating
        if (count == regions.size()) regions.emplace_back();
        ContactRegion& region = regions[count++];
        region.side = side;
        region.deepest = samples[k];
        region.slices.clear();
        region.slices.reserve(samples.size());  // room for every sample: a slot allocates once
      }
      auto& region = regions[count - 1];
      region.slices.push_back(samples[k]);
      if (samples[k].gap < region.deepest.gap) region.deepest = samples[k];
    }
  }
  for (std::size_t r = 0; r < count; ++r) {
    auto& region = regions[r];
    const auto& slices = region.slices;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    double inclination = 0, profile_y = 0, total = 0;
    for (std::size_t k = 0; k < slices.size(); ++k) {
      const GapSample& slice = slices[k];
      const double penetration = -slice.gap;
      // The lateral track length of the slice (trapezoid rule; a lone slice stands for the
      // profile step), never zero, so that a fold of the locus cannot empty a region.
      const double y = slice.wheel.point.y();
      double width = 0;
      if (k > 0) width += std::abs(y - slices[k - 1].wheel.point.y()) / 2;
      if (k + 1 < slices.size()) width += std::abs(slices[k + 1].wheel.point.y() - y) / 2;
      width = std::max(width, slices.size() > 1 ? 1e-3 * options.step : options.step);
      const double weight = width * penetration * penetration * std::sqrt(2 * slice.wheel.radius * penetration);
      weighted += weight * Eigen::Vector3d(slice.wheel.point.x(), slice.wheel.point.y(), slice.rail_z);
      inclination += weight * std::atan(slice.rail_slope);
      profile_y += weight * slice.wheel.profile_y;
      total += weight;
    }
    region.weight = total;
    region.centre = weighted / total;
    region.inclination = inclination / total;
    region.profile_y = profile_y / total;
  }
  // Merge neighbours (ordered by y_w, so by rail position) in place: regions[0, kept) are
  // the merged ones.
  std::size_t kept = 0;
  for (std::size_t r = 0; r < count; ++r) {
    ContactRegion& region = regions[r];
    if (kept > 0) {
      auto& last = regions[kept - 1];
      const auto& a = last.slices.back();
      const auto& b = region.slices.front();
      const double distance = std::hypot(a.wheel.point.y() - b.wheel.point.y(), a.rail_z - b.rail_z);
      if (distance <= options.separation_distance &&
          std::abs(last.inclination - region.inclination) <= options.separation_angle) {
        const double total = last.weight + region.weight;
        last.centre = (last.weight * last.centre + region.weight * region.centre) / total;
        last.inclination = (last.weight * last.inclination + region.weight * region.inclination) / total;
        last.profile_y = (last.weight * last.profile_y + region.weight * region.profile_y) / total;
        last.weight = total;
        if (region.deepest.gap < last.deepest.gap) last.deepest = region.deepest;
        last.slices.insert(last.slices.end(), region.slices.begin(), region.slices.end());
        continue;
      }
    }
    if (kept != r) std::swap(regions[kept], region);
    ++kept;
  }
  return kept;
}

/// The same, returned.
inline std::vector<ContactRegion> contact_regions(const Track& track, const Wheelset& wheelset, Side side,
                                                  const WheelsetPose& pose, const SearchOptions& options = {}) {
  GapSampler sampler;
  std::vector<ContactRegion> regions;
  regions.resize(contact_regions(track, wheelset, side, pose, options, sampler, regions));
  return regions;
}

/// The rigid pose with both wheels just touching their rails (no interpenetration) at
/// lateral shift y and yaw: the roll that equalises the two smallest gaps, then the drop.
inline WheelsetPose rigid_contact_pose(const Track& track, const Wheelset& wheelset, double y, double yaw,
                                       const SearchOptions& options = {}) {
  WheelsetPose pose{y, 0, 0, yaw};
  check_pose(pose, "rigid_contact_pose");
  options.validate();
  auto imbalance = [&](double roll) {
    pose.roll = roll;
    return smallest_gap(track, wheelset, Side::right, pose, options).gap -
           smallest_gap(track, wheelset, Side::left, pose, options).gap;
  };
  // Roll > 0 lowers the right wheel: the imbalance falls with roll. Illinois regula falsi.
  double low = -options.roll_bracket, high = options.roll_bracket, f_low = imbalance(low), f_high = imbalance(high);
  FASTNORM_CHECK(f_low > 0 && f_high < 0,
                 fastnorm::detail::describe("rigid_contact_pose: no roll within ±" + fastnorm::detail::to_text(options.roll_bracket) +
                                                " rad puts both wheels on their rails at this lateral shift (m)",
                                            y));
  int side_kept = 0;
  for (int step = 0; step < options.max_root_steps && high - low > options.roll_tolerance; ++step) {
    const double roll = (low * f_high - high * f_low) / (f_high - f_low);
    const double f = imbalance(roll);
    if (f == 0) {
      low = high = roll;
      break;
    }
    if (f > 0) {
      low = roll, f_low = f;
      if (side_kept == -1) f_high /= 2;
      side_kept = -1;
    } else {
      high = roll, f_high = f;
      if (side_kept == 1) f_low /= 2;
      side_kept = 1;
    }
  }
  pose.roll = (low + high) / 2;
  pose.z = smallest_gap(track, wheelset, Side::right, pose, options).gap;
  return pose;
}

}  // namespace fastnorm::wheelrail
