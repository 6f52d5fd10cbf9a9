// Fitting a smooth profile to measured (or tabulated) profile points: the smoothing spline of
// wear/smoothing_spline.h applied to (y, z) as functions of arc length s, with one lambda for
// both coordinates, chosen by GCV unless given, and outlier rejection plus a Huber loss against
// scan glitches. Used by `railwear profile fit` and for smoothing worn profiles.
//
// The parameter: the arc length of the raw points is the natural one, but a scan glitch (a
// spike) lengthens it by twice the spike's height, so in (s, y, z) the spike is a smooth bump
// that no loss can tell from the profile. The fit's parameter is therefore the arc length along
// a pilot curve (the spline of the raw points in their own arc length with the long smoothing
// length parameter_smoothing_length_m, least squares) at each point's foot point on it: for
// clean points their arc length to within the pilot's smoothing, for a spike the place where
// it sits along the profile, which makes it a plain outlier for the rejection and Huber loss
// of wear/smoothing_spline.h. Points farther from the cubic through their two neighbours on
// each side than reject_threshold times that distance's noise (EstimateProfileNoise, floored
// at min_robust_scale) are the rejection's suspects: on very clean data GCV all but
// interpolates, and residuals alone could not reveal a cluster of glitches.
//
// Measured scans may also carry glitches that make no profile at all: a spike one point wide
// turns the polyline back on itself (a 1 mm spike at 0.1 mm spacing turns it by 168 degrees), a
// point out of scan order steps back, a repeated point duplicates its predecessor. CleanScan
// drops such points one at a time before the fit (see there), so FitProfile sees a valid
// profile, and reports each with the reason; genuinely disordered input stays an error.
//
// Distances reported here are normal (orthogonal) distances of the raw points from the fitted
// curve: the geometric misfit, free of the parameterisation's tangential slack.
#pragma once

#include <string>
#include <vector>

#include "core/profile/profile.h"
#include "wear/smoothing_spline.h"

namespace railwear {

struct ProfileFitOptions {
  // Spline options; t is the arc length s [m], values (y, z) [m], so lambda is in m^4 and the
  // smoothing length lambda^(1/4) in m. Defaults: knots every 0.5 mm, lambda by GCV, gross
  // outliers beyond 10 sigma rejected, Huber loss at 3 sigma, sigma >= 1 um.
  SmoothingSplineOptions spline;
  // Point spacing of the resampled fitted profile along s [m], > 0.
  double output_spacing_m = 0.1e-3;
  // Smoothing length of the pilot curve that gives the parameter [m], > 0. 2 mm: a spike of up
  // to ~2 mm height (a bump ~4 mm wide in the raw arc length) keeps < 3 % of its height in the
  // pilot, while the pilot still follows profile radii down to a few mm.
  double parameter_smoothing_length_m = 2e-3;

  // False with a message naming the first bad option, its value and what was expected.
  bool IsValid(std::string* error) const;
};

struct ProfileFit {
  Profile profile;                 // the fitted curve resampled every ~output_spacing_m
  SmoothingSpline spline;          // (y, z)(s) [m], s the arc length along the pilot
  SmoothingSplineSummary summary;  // the spline fit (residuals there are 2-D vectors at equal s)

  // Signed normal distance of each raw point from the fitted curve [m], shape [n], positive on
  // the side of the fit's LeftNormal() (into the rail for a rail profile).
  std::vector<double> distance_m;
  double rms_distance_m = 0.0;
  double max_distance_m = 0.0;  // largest |distance|
  int max_distance_index = -1;  // its raw point (0-based)
  // Raw points left out as gross outliers (scan glitches), 0-based, ascending.
  std::vector<int> rejected_points;
  int num_rejected = 0;                // rejected_points.size()
  int num_downweighted = 0;            // other raw points the robust loss down-weighted
  double rms_inlier_distance_m = 0.0;  // RMS distance of the points not rejected
  // Noise implied by the fit: sqrt(sum_inliers distance^2 / (n_inliers - tr A)) (Wahba's
  // residual variance estimate) [m]; compare with noise_estimate_m.
  double fit_noise_m = 0.0;

  double lambda_m4 = 0.0;           // penalty weight used
  double smoothing_length_m = 0.0;  // lambda^(1/4): wavelengths below 2 pi this are damped
  // Signed curvature range of the fitted curve [1/m] (sign as Profile::Curvature).
  double curvature_min_per_m = 0.0;
  double curvature_max_per_m = 0.0;
  Eigen::Vector2d curvature_min_at_m = Eigen::Vector2d::Zero();  // (y, z) where they occur [m]
  Eigen::Vector2d curvature_max_at_m = Eigen::Vector2d::Zero();
  // Measurement noise of the raw points estimated independently of the fit [m]
  // (EstimateProfileNoise).
  double noise_estimate_m = 0.0;
};

// A scan made into a profile: the points kept and those dropped as glitches, with why.
struct CleanedScan {
  Profile profile;        // the kept points, source as given
  std::vector<int> kept;  // raw index (0-based) of each profile point, ascending
  struct Dropped {
    int index = 0;       // raw index, 0-based
    std::string reason;  // e.g. "turned the scan back by 168.6 degrees"
  };
  std::vector<Dropped> dropped;  // in the order dropped
};

// The most glitch points CleanScan drops from n points before it calls the scan disordered:
// max(3, 1 %), the budget of the MiniProf readers' glitch dropping (core/profile/profile_io.h).
int MaxScanGlitches(int n);

// Drops the points of `points_m` (shape [n][2], metres, n >= 4) that give the polyline a defect
// (core/profile/profile_defects.h), one defect at a time, first defect first. Of the points
// involved (a duplicate: the repeat; a turn-back at point i: i-1, i, i+1; a crossing of segments
// [a, a+1] and [b, b+1]: their four ends) it drops the one whose removal clears the turns around
// it and that lies farthest from the cubic through its two neighbours on either side (a
// leave-one-out residual, as the fit's outlier suspects): the spike, not its clean neighbours.
// `lines` (shape [n] or empty) are the points' file lines for messages (1-based point numbers
// when empty); `source` names the file. Throws InputError, naming the first remaining defect by
// its lines and coordinates, when more than MaxScanGlitches(n) points would have to go.
CleanedScan CleanScan(const std::vector<Eigen::Vector2d>& points_m, const std::vector<int>& lines,
                      const std::string& source);

// Fits `raw` (n >= 4 points, metres). The resampled profile keeps raw.source() with " (fitted)"
// appended. Throws InputError for invalid options.
ProfileFit FitProfile(const Profile& raw, const ProfileFitOptions& options);

// Normal measurement noise (standard deviation) of a sampled profile [m], from the points alone,
// independent of any fit: e_i is the signed distance of point i from the chord of its neighbours
// (a second difference); the second difference of e, e_{i+1} - 2 e_i + e_{i-1}, removes the
// profile's smooth curvature and its linear change along s, and has variance 17.5 sigma^2 for
// white normal noise on evenly spaced points; sigma = 1.4826 median|...| / sqrt(17.5) (the
// median ignores isolated glitches). Needs n >= 5; returns 0 for fewer points.
double EstimateProfileNoise(const Profile& profile);

}  // namespace railwear
