// CurveLocator: fast geometric queries on one Profile in its own frame — closest point
// (orthogonal projection, seed eq. 2) and intersection with a straight line.
//
// The profile is sampled at a uniform arc-length step for a coarse scan; each answer is then
// refined on the C2 spline by a safeguarded Newton iteration inside the bracket of one sample
// step on either side, to a tolerance far below any cell size (kParameterTolerance_m).
//
// The coarse scan skips whole blocks of kScanBlock samples by their bounding boxes (issue 18
// point 3): a block whose box lies strictly on one side of the line (by more than a rounding
// margin) holds no crossing, and one whose box is farther from the query point than the best
// sample so far holds no closer sample. Every sample a skipped block holds would have lost the
// comparison it skips, so the answers are those of the sample-by-sample scan bit for bit
// (Scan::kEverySample keeps that scan, the reference of curve_locator_test.cpp).
//
// The samples and their blocks' boxes are a function of the profile's points, the orientation
// and the step alone, so locators on the same points share them (issue 18 point 3): every placed
// geometry of a wear step builds locators on the same rails and unyawed wheels, and a wear step's
// load cases on the same yawed outlines. They come from a process-wide cache of the
// kSharedSampleSets most recently used (ProfileKeyedCache: exact keys, under a mutex), so a
// locator answers bit for bit as one that sampled its profile itself.
#pragma once

#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/profile/profile.h"

namespace railwear {

class CurveLocator {
 public:
  static constexpr double kParameterTolerance_m = 1e-12;
  // Samples per bounding box of the coarse scan: 16 samples of 2e-5 m, 0.32 mm of arc
  // (fastest of 8, 16 and 32 on the main job's curving).
  static constexpr int kScanBlock = 16;
  // Sample sets kept for sharing: a rail's or wheel's takes about 0.5 MB with its key (7,500
  // samples of 2e-5 m and the profile's points), so at most about 12 MB. A wear step uses a few
  // rails and wheels and, per vehicle, a few yawed outlines at a time.
  static constexpr size_t kSharedSampleSets = 24;

  // How the coarse scan visits the samples: kBlocks skips blocks by their bounding boxes (the
  // default), kEverySample tests each one (the reference; same answers bit for bit).
  enum class Scan { kBlocks, kEverySample };

  // material_toward_plus_z: true for a rail (material below its surface, at larger z), false for
  // a wheel (material above). Decides the sign of SignedDistance. `sample_step_m` is the coarse
  // scan step in arc length.
  CurveLocator(const Profile& profile, bool material_toward_plus_z, double sample_step_m = 2e-5,
               Scan scan = Scan::kBlocks);

  const Profile& profile() const { return *profile_; }

  struct Projection {
    double s = 0.0;  // arc length of the closest point [m]
    Eigen::Vector2d point = Eigen::Vector2d::Zero();
    double signed_distance = 0.0;  // > 0 outside the body, < 0 inside [m]
  };
  // Closest point to q among profile parameters in [s_lo, s_hi] (clipped to the profile).
  Projection Project(const Eigen::Vector2d& q, double s_lo, double s_hi) const;
  Projection Project(const Eigen::Vector2d& q) const { return Project(q, 0.0, length_); }

  // Project(q, s_lo, s_hi) started at s_start (a neighbouring query's answer): Newton's
  // iteration from s_start over [s_lo, s_hi] without the closest-sample scan, kept only where
  // the profile's bounds over the scan's samples prove the distance has no other critical point
  // there (its derivative g' = |C'|^2 + (C - q) . C'' > 0: |C - q| |C''| < |C'|^2); otherwise
  // Project's scan. The same closest point as Project's within kParameterTolerance_m (both end
  // within it of the one root of g; the last bits may differ).
  Projection ProjectFrom(const Eigen::Vector2d& q, double s_start, double s_lo, double s_hi) const;

  // Outward unit normal (pointing out of the body's material) at parameter s.
  Eigen::Vector2d OutwardNormal(double s) const;

  // Intersection of the line b + lambda * n (unit n; t = n rotated, the line's normal direction
  // for the search) with the profile, among parameters in [s_lo, s_hi]: the crossing with the
  // smallest |lambda|. Returns the parameter and lambda, or nullopt when the line misses.
  struct Crossing {
    double s = 0.0;
    double lambda = 0.0;
  };
  std::optional<Crossing> IntersectLine(const Eigen::Vector2d& b, const Eigen::Vector2d& n,
                                        double s_lo, double s_hi) const;

  // IntersectLine(b, n, s_lo, s_hi) started at s_start (a neighbouring line's crossing):
  // Newton's iteration over the scan's samples without the scan, kept only where the profile's
  // bounds prove that (C - b) . t is monotonic there (|C'(s) . t| > |C''| |s - s_c| about the
  // crossing s_c found), so that the scan would find this crossing alone; otherwise
  // IntersectLine. The same crossing within kParameterTolerance_m.
  std::optional<Crossing> IntersectLineFrom(const Eigen::Vector2d& b, const Eigen::Vector2d& n,
                                            double s_start, double s_lo, double s_hi) const;

  double length() const { return length_; }

  // True when both locators use the same shared samples (for tests of the sharing).
  bool SharesSamplesWith(const CurveLocator& other) const { return samples_ == other.samples_; }

 private:
  struct Samples;
  // The closest point's parameter; *evaluated is set when the last evaluation was at it, with
  // the position and derivative there in *c_at and *d1_at.
  double RefineClosest(const Eigen::Vector2d& q, double s0, double lo, double hi,
                       Eigen::Vector2d* c_at, Eigen::Vector2d* d1_at, bool* evaluated) const;
  // Index of the sample in [i0, i1] closest to q, the first of equals (the scan's choice).
  int ClosestSample(const Eigen::Vector2d& q, int i0, int i1) const;
  // Newton's refinement of the crossing in [s_{i-1}, s_i] given phi there (IntersectLine).
  Crossing RefineCrossing(const Eigen::Vector2d& b, const Eigen::Vector2d& n,
                          const Eigen::Vector2d& t, int i, double prev, double cur) const;
  // The same from s in [lo, hi], phi(lo) = flo of the other sign than phi(hi); *converged is
  // set when it ended on a root (phi = 0 or a Newton step below tolerance), *slope to phi' there.
  Crossing RefineCrossingFrom(const Eigen::Vector2d& b, const Eigen::Vector2d& n,
                              const Eigen::Vector2d& t, double s, double lo, double hi, double flo,
                              bool* converged, double* slope) const;
  // The projection onto the profile at s with position and derivative c, d1 there.
  Projection MakeProjection(const Eigen::Vector2d& q, double s, const Eigen::Vector2d& c,
                            const Eigen::Vector2d& d1) const;
  // Bounds over blocks k0..k1 (their samples and knots): max |C''|, min and max |C'|.
  struct Bounds {
    double d2_max, speed_min, speed_max;
  };
  Bounds BlockBounds(int k0, int k1) const;
  // The samples a search over [s_lo, s_hi] scans: the first at or below s_lo, the last at or
  // above s_hi, within the profile's.
  std::pair<int, int> SampleRange(double s_lo, double s_hi) const;
  // Squared distance from q to block k's box (a lower bound on its samples' squared
  // distances), and the range of (p - b) . t over the box.
  double BlockDistance2(int k, const Eigen::Vector2d& q) const;
  bool BlockOnOneSide(int k, const Eigen::Vector2d& b, const Eigen::Vector2d& t,
                      double margin) const;
  const Profile* profile_;
  double length_ = 0.0;
  Scan scan_ = Scan::kBlocks;
  std::shared_ptr<const Samples> samples_;
  // Copies of samples_'s scalars and plain pointers into its arrays, for the scans.
  double step_ = 0.0;
  double outward_sign_ = 1.0;  // OutwardNormal = outward_sign_ * LeftNormal
  int n_samples_ = 0;
  const double* sample_s_ = nullptr;
  const Eigen::Vector2d* sample_p_ = nullptr;
  // Block k holds samples [k kScanBlock, (k + 1) kScanBlock] (the last one shared with the
  // next block, so that each pair of neighbours lies in one block); its bounding box.
  int n_boxes_ = 0;
  const Eigen::Vector2d* box_lo_ = nullptr;
  const Eigen::Vector2d* box_hi_ = nullptr;
  const Bounds* block_bounds_ = nullptr;  // per block, for ProjectFrom and IntersectLineFrom
  double max_abs_coordinate_ = 0.0;  // of the samples [m], for the rounding margin
};

}  // namespace railwear
