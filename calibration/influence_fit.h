// Fitting the constants of the seed's eq. 4 (c_f, c_z, c_s: one set for both bodies, or a
// convex and a concave set) to reference data with Ceres: the library behind `railwear
// calibrate` (issue 5).
//
// Data of two kinds, each with a weight:
//  1. Displacement curves (displacement_curves.h): the seed's experiment on a convex, concave or
//     flat body. A *curve* is one file x load x path (e.g. the normal load seen along the arc);
//     points closer to the load than min_distance_m (an FE model's near field) or farther than
//     max_distance_m are left out.
//  2. Contact results: a contact problem (a scene) with a target contact area and peak pressure.
//
// Residuals (all dimensionless; the cost is half their sum of squares):
//  - a curve point:   r = sqrt(weight) (w_model(c) + o_curve - w_data) / S_curve,
//    w_model from SeedKernelDisplacement with the trial constants, S_curve the RMS of the curve's
//    data in the window. Scaling by the curve's own RMS makes curves of different magnitude
//    (a normal load on R 15 mm and a tangential one on R 80 mm differ tenfold) weigh alike per
//    point, and makes the residuals homoscedastic when the reference's error is proportional to
//    the displacement, as an FE model's discretisation error is. Each point is one residual, so
//    a curve of 40 points counts 40 times as much as one contact residual; the weights balance
//    that.
//  - the offset o_curve (fit_offsets, the default): a finite FE body on clamped supports
//    deflects by a support-dependent amount that a half-space has not (a clamped boundary
//    200 mm away still costs ~4 % at 5 mm from the load and ~17 % at 20 mm), while only
//    differences of displacement across a patch matter for contact. One free offset per curve
//    (parameter t = o / S_curve, unbounded) removes it. It starts at the best offset for the
//    starting constants (the mean of data - model), so the residuals "before" measure the
//    starting constants, not the supports.
//  - a contact result: r_area = sqrt(weight) (A(c) / A_target - 1) and
//    r_p = sqrt(weight) (p_max(c) / p_max_target - 1), A and p_max from SolveContact on the
//    target's problem with the trial constants: exactly what a scene run with these constants
//    computes (its accuracy preset, re-gridding included). Derivatives by central differences
//    with the step h = contact_relative_step * max(|c|, 0.1) (forward differences where c - h
//    would cross the lower bound). The default step, 1 %, is large on purpose: the area estimate
//    is quantised (the level-set area is sub-sampled on 24 x 24 points in each boundary square)
//    and the contact set changes by whole cells, so the area is only piecewise smooth in the
//    constants; 1 % spans many of its steps, while the truncation error on the smooth p_max
//    stays O(h^2) ~ 1e-4 relative.
// The displacement model is affine in each constant, so its derivatives are exact (the
// difference of SeedKernelDisplacement at c_k + 1 and c_k).
//
// Bounds (physical): c_f >= 1e-3 and c_z >= 1e-3 (positive kernels; scenes refuse 0), and
// c_t = 1 + c_s sign >= 1e-3 for the bodies a set applies to: c_s in [-0.999, 0.999] for one
// set, c_s <= 0.999 for a convex set, c_s >= -0.999 for a concave set. A constant that ends on
// its bound is reported (its standard error then means little).
//
// Standard errors: the data have no known noise, so the covariance (J^T J)^-1 of
// ceres::Covariance (DENSE_SVD, over the free constants and offsets) is scaled by the residual
// variance s^2 = 2 cost / (N - p), N residuals, p free parameters (constants and offsets).
// Correlations are free of that scale.
//
// Conditioning is reported, never hidden (a badly conditioned fit is a warning in the summary,
// not an exception):
//  - a constant whose Jacobian column at the start is (near) zero, below
//    min_relative_sensitivity of the largest column, is not determined by the data: it is held
//    at its starting value and reported with the reason ("c_s: no tangential-load curve",
//    "c_z: no normal-load curve with out-of-plane offsets (axis-only data)", ...);
//  - the singular values and the condition number of the column-scaled Jacobian at the
//    solution (each column divided by its norm, so units do not matter), with a warning above
//    condition_warning;
//  - pairs of free parameters (constants and offsets) with |correlation| > correlation_warning;
//  - when ceres::Covariance cannot be computed (a rank-deficient Jacobian: e.g. the convex and
//    the concave c_f fitted to contact results alone, which see only their sum), the summary
//    says so and still returns the fit, without standard errors.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "calibration/displacement_curves.h"
#include "core/contact/contact_solver.h"
#include "core/contact/contact_types.h"

namespace railwear {

enum class InfluenceConstantName { kCf, kCz, kCs };
std::string_view ToString(InfluenceConstantName v);  // "c_f", "c_z", "c_s"
std::optional<InfluenceConstantName> InfluenceConstantNameFromString(std::string_view s);

// One displacement-curve file with its weight and distance window.
struct CurveDataSet {
  DisplacementCurves curves;  // as read by ReadDisplacementCurves (or built in memory)
  double weight = 1.0;        // > 0
  // Points with distance_m outside [min_distance_m, max_distance_m] are left out [m].
  double min_distance_m = 0.0;                                      // >= 0
  double max_distance_m = std::numeric_limits<double>::infinity();  // > min_distance_m
};

// A contact result to match.
struct ContactTarget {
  std::string name;        // for reports (e.g. the scene file)
  ContactProblem problem;  // its model must use the golubenko kernel (the constants' kernel)
  double area_m2 = 0.0;    // target contact area, > 0 [m^2]
  double p_max_Pa = 0.0;   // target peak pressure, > 0 [Pa]
  double weight = 1.0;     // > 0
};

struct InfluenceFitData {
  std::vector<CurveDataSet> curves;
  std::vector<ContactTarget> contacts;
};

struct InfluenceFitOptions {
  // The constants to fit: any non-empty subset, each at most once. With separate_bodies each is
  // fitted in both the convex and the concave set.
  std::vector<InfluenceConstantName> fit = {InfluenceConstantName::kCf, InfluenceConstantName::kCz,
                                            InfluenceConstantName::kCs};
  // One set for both bodies (false) or a convex and a concave set (true; flat-body curves are
  // then refused: a flat body belongs to neither set).
  bool separate_bodies = false;
  // Starting values, and the values of the constants not fitted. With separate_bodies a single
  // set starts both sets; without, `start` must not be separate. Must lie within the bounds.
  InfluenceConstants start;
  // One free offset per displacement curve (see the file comment).
  bool fit_offsets = true;
  // Relative step of the central differences on contact results, in (0, 0.5].
  double contact_relative_step = 1e-2;

  // Ceres (Levenberg-Marquardt, dense QR): iteration limit >= 1 and tolerances > 0.
  int max_num_iterations = 100;
  double function_tolerance = 1e-10;
  double gradient_tolerance = 1e-12;
  double parameter_tolerance = 1e-8;

  // Conditioning report. A constant whose Jacobian column norm at the start is below
  // min_relative_sensitivity (in [0, 1)) times the largest is "not determined" and held fixed;
  // a condition number of the column-scaled Jacobian above condition_warning (> 1) and a
  // |correlation| above correlation_warning (in (0, 1]) are warnings. 100 is where a pair's
  // |correlation| reaches 0.9998, or 1 % of relative data error becomes 100 % in a parameter.
  double min_relative_sensitivity = 1e-8;
  double condition_warning = 100.0;
  double correlation_warning = 0.95;

  // False with a message naming the first bad option, its value and what was expected.
  bool IsValid(std::string* error) const;
};

enum class InfluenceFitStatus {
  kConverged,      // Ceres reported convergence
  kNoConvergence,  // iteration limit reached; the constants are the last (usable) iterate
  kFailure,        // Ceres failed, or a contact solve at the start did not converge
};
std::string_view ToString(InfluenceFitStatus v);  // "converged", "no-convergence", "failure"

// One fitted constant.
struct FittedConstant {
  std::string name;  // "c_f", or "convex.c_f" / "concave.c_f" with separate sets
  double start = 0.0;
  double value = 0.0;
  // Standard error (scaled by s^2); NaN when not determined or the covariance is unavailable.
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  bool determined = true;          // false: no sensitivity in these data; held at `start`
  std::string why_not_determined;  // the reason, when not determined
  bool at_bound = false;           // the fit ended on a bound
};

// One point of a displacement curve, before (starting constants) and after the fit. The model
// includes the curve's offset. Residual = model - data.
struct CurvePointResidual {
  int line = 0;  // in the data file (0 when built in memory)
  double distance_m = 0.0;
  double data_m_per_N = 0.0;
  double model_before_m_per_N = 0.0;
  double model_after_m_per_N = 0.0;
};

struct CurveFitReport {
  std::string file;  // DisplacementCurves::path
  CurveBody body = CurveBody::kFlat;
  double radius_m = 0.0;
  CurveLoad load = CurveLoad::kNormal;
  CurvePath path = CurvePath::kArc;
  double weight = 1.0;
  double scale_m_per_N = 0.0;  // S_curve: RMS of the data in the window
  // The curve's offset [m/N] before (the best one for the starting constants) and after; 0
  // without fit_offsets. Its standard error [m/N]; NaN when unavailable.
  double offset_before_m_per_N = 0.0;
  double offset_after_m_per_N = 0.0;
  double offset_standard_error_m_per_N = std::numeric_limits<double>::quiet_NaN();
  std::vector<CurvePointResidual> points;  // in file order
  int points_left_out = 0;                 // outside the distance window
  // RMS and largest |residual| / S_curve, before and after.
  double rms_before = 0.0, max_before = 0.0, rms_after = 0.0, max_after = 0.0;

  // "FILE: normal load, arc" (the file's name without its folder).
  std::string Name() const;
};

struct ContactFitReport {
  std::string name;
  double weight = 1.0;
  double target_area_m2 = 0.0, target_p_max_Pa = 0.0;
  double area_before_m2 = 0.0, p_max_before_Pa = 0.0;  // with the starting constants
  double area_after_m2 = 0.0, p_max_after_Pa = 0.0;    // with the fitted constants
};

struct InfluenceFitSummary {
  InfluenceFitStatus status = InfluenceFitStatus::kFailure;
  std::string message;  // Ceres's termination message, or why the fit failed

  InfluenceConstants start;               // as used (separate when separate_bodies)
  InfluenceConstants fitted;              // start with the fitted constants in place
  std::vector<FittedConstant> constants;  // the fitted constants, in parameter order
  // Correlations among `constants` [constants x constants]; NaN in the rows and columns of
  // constants without a covariance; empty when the covariance is unavailable.
  Eigen::MatrixXd correlation;
  bool covariance_available = false;
  std::string covariance_message;  // why not, when unavailable

  int num_residuals = 0;
  int num_free_parameters = 0;  // determined constants + offsets
  double cost_before = 0.0;     // 1/2 sum r^2 at the start (best offsets)
  double cost_after = 0.0;
  double residual_variance = 0.0;  // s^2 = 2 cost_after / (N - p); 0 when N <= p
  // Singular values (descending) and condition number of the column-scaled Jacobian of the free
  // parameters at the solution.
  std::vector<double> singular_values;
  double condition_number = 0.0;
  // False when a constant is not determined, the condition number or a correlation is above its
  // threshold, or the covariance could not be computed.
  bool well_conditioned = true;
  std::vector<std::string> warnings;  // conditioning and other findings, one sentence each

  std::vector<CurveFitReport> curves;
  std::vector<ContactFitReport> contacts;

  int iterations = 0;      // Levenberg-Marquardt iterations
  int contact_solves = 0;  // SolveContact calls (all targets, derivatives included)
  double time_s = 0.0;
  std::string ceres_brief_report;
  std::string ceres_full_report;

  // One line: status, constants with standard errors, residuals before/after, conditioning.
  std::string BriefReport() const;
};

// Fits the constants. Throws InputError for invalid options or data (empty data, weights or
// windows out of range, a data set without points in its window, a curve whose data are all
// zero, a flat-body curve with separate_bodies, a contact target that does not use the
// golubenko kernel or has non-positive targets), naming the file or target.
InfluenceFitSummary FitInfluenceConstants(const InfluenceFitData& data,
                                          const InfluenceFitOptions& options);

}  // namespace railwear
