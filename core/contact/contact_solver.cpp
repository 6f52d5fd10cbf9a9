// SolveContact: placement -> contact search -> patch grids and gaps -> influence -> normal solve.
//
// The potential contact area is not known before the solve. It starts from a Hertz estimate of
// the approach at the first contact point and is corrected from the solution: the grid grows
// when pressure reaches its edge, takes in further candidates (two-point contact) when the
// approach passes their gap, and is re-gridded when the patch turns out larger or smaller than
// estimated, so that every accuracy preset keeps its number of cells per semi-axis.
#include "core/contact/contact_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include <fmt/format.h>

#include "core/contact/coupling.h"
#include "core/contact/fastsim.h"
#include "core/contact/grid_resolution.h"
#include "core/contact/tangential_exact.h"
#include "core/contact/influence_operator.h"
#include "core/contact/model_selection.h"
#include "core/geometry/patch_builder.h"
#include "core/geometry/wheel_rail_geometry.h"
#include "core/numerics/check.h"
#include "core/numerics/input_error.h"

namespace railwear {

namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void AddStage(std::vector<StageTime>* stages, const std::string& name, double seconds) {
  for (auto& s : *stages) {
    if (s.name == name) {
      s.seconds += seconds;
      return;
    }
  }
  stages->push_back({name, seconds});
}

// Hertz's relative curvatures at a candidate: A along x (the wheel's parallel circle, normal
// curvature cos(gamma)/r by Meusnier, gamma the angle between the contact normal and the wheel's
// radial direction, which the wheel's roll turns away from the vertical), B laterally (sum of the
// convex-positive profile curvatures); w0 the normal's cosine against the vertical.
// B is bounded below to stay meaningful in nearly conformal contact, where it only seeds the
// estimate of the approach.
struct Curvatures {
  double A = 0.0, B = 0.0, w0 = 1.0;
};
Curvatures CandidateCurvatures(const ContactCandidate& c, double roll_rad) {
  Curvatures k;
  k.w0 = std::max(-c.normal.y(), 1e-3);
  // The wheel's radial direction (toward the rail) in R: (-sin roll, cos roll).
  const double cos_gamma = c.normal.x() * std::sin(roll_rad) - c.normal.y() * std::cos(roll_rad);
  k.A = std::max(cos_gamma, 1e-3) / (2.0 * c.wheel_radius_m);
  k.B = std::max(0.5 * (c.rail_lateral_curvature + c.wheel_lateral_curvature), 1e-4 * k.A);
  return k;
}

// Vertical approach for which Hertz contacts at all candidates carry the vertical load F
// (bisection on the common approach), or their loads for a given approach.
double HertzVerticalLoad(const std::vector<ContactCandidate>& cands, double roll_rad,
                         double estar, double delta, std::vector<HertzSolution>* out) {
  double total = 0.0;
  if (out) out->clear();
  for (const auto& c : cands) {
    const Curvatures k = CandidateCurvatures(c, roll_rad);
    const double dn = std::max(0.0, (delta - c.gap_m) * k.w0);
    const HertzSolution h = SolveHertzForApproach(k.A, k.B, estar, dn);
    total += h.force_N * k.w0;
    if (out) out->push_back(h);
  }
  return total;
}

double HertzApproachForLoad(const std::vector<ContactCandidate>& cands, double roll_rad,
                            double estar, double force) {
  double hi = 1e-6;
  while (HertzVerticalLoad(cands, roll_rad, estar, hi, nullptr) < force && hi < 1.0) hi *= 2.0;
  double lo = 0.0;
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (HertzVerticalLoad(cands, roll_rad, estar, mid, nullptr) < force ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

PatchResult HertzPatch(const ContactCandidate& c, const HertzSolution& h) {
  PatchResult p;
  p.hertz = h;
  p.area_m2 = h.area_m2;
  p.p_max_Pa = h.p0_Pa;
  p.normal_force_N = h.force_N;
  p.vertical_force_N = h.force_N * (-c.normal.y());
  p.lateral_force_N = h.force_N * (-c.normal.x());
  p.contact_point_yz_m = c.rail_point_m;
  p.contact_angle_rad = std::atan2(p.lateral_force_N, p.vertical_force_N);
  return p;
}

// The Hertz model's candidates and common approach: candidates within a generous threshold,
// widened while the approach passes it; hs[k] is candidate k's ellipse (force 0: no contact).
struct HertzSearch {
  std::vector<ContactCandidate> cands;
  std::vector<HertzSolution> hs;
  double delta = 0.0;
};
HertzSearch SearchHertz(const WheelRailGeometry& geom, const ContactProblem& problem,
                        double estar) {
  HertzSearch out;
  double threshold = 1e-4;
  for (int attempt = 0; attempt < 20; ++attempt) {
    out.cands = geom.FindCandidates(threshold);
    out.delta = problem.load.approach_m
                    ? *problem.load.approach_m
                    : HertzApproachForLoad(out.cands, problem.placement.roll_rad, estar,
                                           *problem.load.vertical_force_N);
    if (out.delta < 0.8 * threshold) break;
    threshold = 2.0 * out.delta;
  }
  HertzVerticalLoad(out.cands, problem.placement.roll_rad, estar, out.delta, &out.hs);
  return out;
}

ContactResult SolveHertzModel(const HertzSearch& search, ContactResult result,
                              Clock::time_point t0) {
  result.approach_m = search.delta;
  for (size_t k = 0; k < search.cands.size(); ++k) {
    if (search.hs[k].force_N <= 0) continue;
    result.patches.push_back(HertzPatch(search.cands[k], search.hs[k]));
    result.patches.back().model = "hertz";
  }
  result.status = result.patches.empty() ? SolverStatus::kNoContact : SolverStatus::kConverged;
  if (result.patches.empty()) result.message = "no contact at this approach";
  AddStage(&result.stages, "hertz", SecondsSince(t0));
  return result;
}

// Lateral semi-axis (arc length) of a candidate's patch at the vertical approach delta, for the
// auto model's criterion: Hertz's b, and the lateral reach of the interpenetration at delta
// divided by sqrt(2) (equal to b for Hertz's quadratic gap; smaller in nearly conformal contact,
// where Hertz's b is far too large; larger where the gap flattens and the patch spreads). `lo`
// is the smaller of the two (the first grid estimate of SolveContact), `hi` the larger. A
// candidate that delta does not reach yet gets the reach of its potential area (its interval).
// at_delta: geom.FindCandidates(delta).
struct SemiAxisEstimate {
  double lo = 0.0, hi = 0.0;
};
SemiAxisEstimate EstimateSemiAxisS(const WheelRailGeometry& geom, const ContactCandidate& c,
                                   double estar, double delta,
                                   const std::vector<ContactCandidate>& at_delta) {
  constexpr double kMinSemiAxis_m = 1e-5;
  static constexpr double kMinApproachWeight = 0.1;  // as the reach bound of SolveContact
  const Curvatures k = CandidateCurvatures(c, geom.pose().roll_rad);
  const double dn = (delta - c.gap_m) * k.w0;
  auto reach_of = [](const ContactCandidate& ci) {
    return 0.5 * (ci.y_hi_m - ci.y_lo_m) / std::max(-ci.normal.y(), kMinApproachWeight);
  };
  if (!(dn > 0)) {
    const double b = std::max(reach_of(c) / std::sqrt(2.0), kMinSemiAxis_m);
    return {b, b};
  }
  const double hertz_b = SolveHertzForApproach(k.A, k.B, estar, dn).semi_axis_y_m;
  SemiAxisEstimate e{hertz_b, hertz_b};
  for (const auto& ci : at_delta) {
    if (c.y_m >= ci.y_lo_m && c.y_m <= ci.y_hi_m) {
      const double reach_b = reach_of(ci) / std::sqrt(2.0);
      e = {std::min(hertz_b, reach_b), std::max(hertz_b, reach_b)};
    }
  }
  e.lo = std::max(e.lo, kMinSemiAxis_m);
  e.hi = std::max(e.hi, kMinSemiAxis_m);
  return e;
}

// Measured extent of the contact on a grid: half-lengths along x and s of the cells with p > 0.
struct Extent {
  double half_x = 0.0, half_s = 0.0;
  double s_lo = 0.0, s_hi = 0.0;  // s range of the cells in contact, cell edges included
  bool touches_x_edge = false, touches_s_edge = false;
  int cells = 0;
};
Extent MeasureExtent(const PatchGrid& g, const Eigen::Ref<const Eigen::VectorXd>& p) {
  Extent e;
  double s_lo = 1e300, s_hi = -1e300;
  for (int j = 0; j < g.ns; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      if (p[g.Index(i, j)] <= 0) continue;
      ++e.cells;
      e.half_x = std::max(e.half_x, std::abs(g.X(i)) + 0.5 * g.dx_m);
      s_lo = std::min(s_lo, g.S(j) - 0.5 * g.ds_m);
      s_hi = std::max(s_hi, g.S(j) + 0.5 * g.ds_m);
      if (i == 0 || i == g.nx - 1) e.touches_x_edge = true;
      if (j == 0 || j == g.ns - 1) e.touches_s_edge = true;
    }
  }
  if (e.cells > 0) {
    e.half_s = 0.5 * (s_hi - s_lo);
    e.s_lo = s_lo;
    e.s_hi = s_hi;
  }
  return e;
}

// Contact area with the edge located inside the boundary cells (a level-set estimate).
// p^2 is a smooth function that crosses zero at the contact edge (for Hertz it is the quadratic
// p0^2 (1 - x^2/a^2 - y^2/b^2)). Take phi = p^2 at cells in contact; at cells out of contact next
// to the contact (8-neighbourhood), extrapolate p^2 quadratically along each line through
// contact cells (phi = 3 f0 - 3 f1 + f2 from the three cells on the line, linear 2 f0 - f1 when
// only two are in contact) and average; the area is that of {phi > 0} under the bilinear
// interpolation of phi between cell centres. Second order in the cell size, where counting whole
// cells overestimates the area by about 0.3 / (cells per semi-axis) on Hertz cases.
double SubCellArea(const PatchGrid& g, const Eigen::Ref<const Eigen::VectorXd>& p) {
  const int nx = g.nx, ns = g.ns;
  auto inside = [&](int i, int j) { return i >= 0 && j >= 0 && i < nx && j < ns; };
  auto p2 = [&](int i, int j) {
    if (!inside(i, j)) return 0.0;
    const double v = p[g.Index(i, j)];
    return v > 0 ? v * v : 0.0;
  };
  double p2max = 0.0;
  for (int k = 0; k < p.size(); ++k) p2max = std::max(p2max, p[k] > 0 ? p[k] * p[k] : 0.0);
  if (p2max <= 0) return 0.0;
  const double far = -p2max;  // level of cells away from the contact
  std::vector<double> phi(static_cast<size_t>(nx) * ns, far);
  for (int j = 0; j < ns; ++j) {
    for (int i = 0; i < nx; ++i) {
      double& f = phi[g.Index(i, j)];
      const double own = p2(i, j);
      if (own > 0) {
        f = own;
        continue;
      }
      double sum = 0.0;
      int count = 0;
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          if (di == 0 && dj == 0) continue;
          const double f0 = p2(i - di, j - dj);
          if (f0 <= 0) continue;
          const double f1 = p2(i - 2 * di, j - 2 * dj);
          const double f2 = p2(i - 3 * di, j - 3 * dj);
          double e = (f1 > 0 && f2 > 0) ? 3 * f0 - 3 * f1 + f2 : (f1 > 0 ? 2 * f0 - f1 : -f0);
          sum += std::min(e, -1e-12 * p2max);  // out of contact: strictly negative
          ++count;
        }
      }
      if (count > 0) f = sum / count;
    }
  }
  // Area of {phi > 0} over the squares between cell centres; mixed squares by sub-sampling the
  // bilinear interpolant on kSub x kSub points (its error is far below the level-set error).
  constexpr int kSub = 24;
  double cells = 0.0;
  for (int j = 0; j + 1 < ns; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const double a = phi[g.Index(i, j)], b = phi[g.Index(i + 1, j)];
      const double c = phi[g.Index(i, j + 1)], d = phi[g.Index(i + 1, j + 1)];
      const int positive = (a > 0) + (b > 0) + (c > 0) + (d > 0);
      if (positive == 0) continue;
      if (positive == 4) {
        cells += 1.0;
        continue;
      }
      int hit = 0;
      for (int v = 0; v < kSub; ++v) {
        const double t = (v + 0.5) / kSub;
        for (int u = 0; u < kSub; ++u) {
          const double r = (u + 0.5) / kSub;
          const double f = (1 - r) * (1 - t) * a + r * (1 - t) * b + (1 - r) * t * c + r * t * d;
          hit += f > 0;
        }
      }
      cells += static_cast<double>(hit) / (kSub * kSub);
    }
  }
  return cells * g.CellArea();
}

PatchResult NumericalPatch(const WheelRailGeometry& geom, PatchGrid grid,
                           const Eigen::Ref<const Eigen::VectorXd>& p) {
  PatchResult r;
  const double area = grid.CellArea();
  double fy = 0.0, fz = 0.0, fn = 0.0, ps = 0.0, psum = 0.0;
  for (int j = 0; j < grid.ns; ++j) {
    const Eigen::Vector2d n = grid.normal_yz[j];
    for (int i = 0; i < grid.nx; ++i) {
      const double pk = p[grid.Index(i, j)];
      if (pk <= 0) continue;
      ++r.cells_in_contact;
      fn += pk * area;
      fy += pk * area * (-n.x());
      fz += pk * area * (-n.y());
      ps += pk * grid.S(j);
      psum += pk;
      r.p_max_Pa = std::max(r.p_max_Pa, pk);
    }
  }
  r.cells = grid.cells();
  r.area_m2 = SubCellArea(grid, p);
  r.normal_force_N = fn;
  r.vertical_force_N = fz;
  r.lateral_force_N = fy;
  r.contact_angle_rad = std::atan2(fy, fz);
  if (psum > 0) {
    // Pressure centre on the reference cross-section, projected onto the rail profile.
    const double sbar = ps / psum;
    const double jf = std::clamp((sbar - grid.s0_m) / grid.ds_m, 0.0, grid.ns - 1.0);
    const int j0 = std::min(static_cast<int>(jf), std::max(grid.ns - 2, 0));
    const int j1 = std::min(j0 + 1, grid.ns - 1);
    const double f = jf - j0;
    const Eigen::Vector2d q = (1 - f) * grid.point_yz_m[j0] + f * grid.point_yz_m[j1];
    r.contact_point_yz_m = geom.rail().Project(q).point;
  }
  r.grid = std::move(grid);
  r.pressure_Pa = p;
  return r;
}

// The rolling stage on every numerical patch: rigid slip per cell (from the wheel's motion or
// prescribed creepages), its patch average, and the tangential solution.
void SolveRolling(const ContactProblem& problem, const WheelRailGeometry& geom,
                  ContactResult* result) {
  const RollingOptions& o = *problem.rolling;
  result->pitch_velocity_rad_s =
      o.motion.pitch_velocity_rad_s.value_or(-o.motion.speed_m_s / problem.placement.rolling_radius_m);
  const CombinedElastic elastic = CombineElastic(problem.wheel_material, problem.rail_material);
  for (PatchResult& patch : result->patches) {
    const RollingInput in =
        o.creepage ? RigidSlipFromCreepage(patch.grid, patch.pressure_Pa, *o.creepage,
                                           o.motion.speed_m_s, o.friction)
                   : RigidSlipFromMotion(geom, patch.grid, o.motion, o.friction);
    RollingPatch rolling;
    rolling.creepage = AverageCreepage(patch.grid, patch.pressure_Pa, in);
    if (o.method == TangentialMethod::kExact) {
      rolling.tangential = SolveTangentialExact(patch.grid, patch.pressure_Pa, in,
                                                problem.wheel_material, problem.rail_material,
                                                ExactTangentialOptions{});
    } else {
      FastsimOptions fo;
      fo.shear_modulus_Pa = elastic.shear_modulus_Pa;
      fo.poisson_ratio = elastic.poisson_ratio;
      rolling.tangential = SolveFastsim(patch.grid, patch.pressure_Pa, in, fo);
    }
    // The patch's equivalent ellipse (the semi-axes FASTSIM uses), for the damage indices.
    const ContactEllipse used = EstimateContactEllipse(patch.grid, patch.pressure_Pa);
    rolling.semi_axis_x_m = used.semi_axis_x_m;
    rolling.semi_axis_s_m = used.semi_axis_s_m;
    if (o.damage && rolling.tangential.status == SolverStatus::kConverged) {
      PatchDamageInput d;
      d.force_x_N = rolling.tangential.force_x_N;
      d.force_y_N = rolling.tangential.force_s_N;
      d.normal_force_N = patch.normal_force_N;
      d.xi = rolling.creepage.xi;
      d.eta = rolling.creepage.eta;
      d.semi_axis_x_m = used.semi_axis_x_m;
      d.semi_axis_y_m = used.semi_axis_s_m;
      d.shear_yield_Pa = problem.rail_material.shear_yield_Pa;
      rolling.damage = CalcPatchDamage(d);
    }
    patch.rolling = std::move(rolling);
  }
}

double TotalForceX(const ContactResult& r) {
  double fx = 0.0;
  for (const auto& p : r.patches) fx += p.rolling ? p.rolling->tangential.force_x_N : 0.0;
  return fx;
}

double TotalNormalForce(const ContactResult& r) {
  double fn = 0.0;
  for (const auto& p : r.patches) fn += p.normal_force_N;
  return fn;
}

// The rolling stage with a prescribed total longitudinal force: the pitch velocity is solved for.
void SolveRollingForForce(const ContactProblem& problem, const WheelRailGeometry& geom,
                          ContactResult* result) {
  ContactProblem trial = problem;
  const RollingOptions& o = *problem.rolling;
  const double target = *o.longitudinal_force_N;
  auto fx = [&](double omega) {
    trial.rolling->motion.pitch_velocity_rad_s = omega;
    SolveRolling(trial, geom, result);
    return TotalForceX(*result);
  };
  const double tolerance = 1e-6 * o.friction * TotalNormalForce(*result);
  const auto omega = SolvePitchVelocityForForce(fx, target, o.motion.speed_m_s,
                                                problem.placement.rolling_radius_m, tolerance);
  if (!omega) {
    result->status = SolverStatus::kNotConverged;
    result->message = fmt::format(
        "the longitudinal force {:.1f} N cannot be carried: friction limits it to about "
        "{:.1f} N here (mu F_n = {:.1f} N)",
        target, std::abs(TotalForceX(*result)), o.friction * TotalNormalForce(*result));
    return;
  }
  fx(*omega);  // leave the result at the solution
}

// The coupling effect: the tangential tractions add CouplingDisplacement to each patch's gap;
// the normal and rolling stages are repeated until the pressure settles.
void SolveCoupled(const ContactProblem& problem, const WheelRailGeometry& geom,
                  const std::vector<ContactCandidate>& cands, const std::vector<int>& kept_build,
                  const std::vector<int>& kept_offset, NormalProblem* np,
                  Eigen::VectorXd pressure, ContactResult* result) {
  const RollingOptions& o = *problem.rolling;
  auto totals = [](const ContactResult& r) {
    double area = 0.0, p_max = 0.0;
    for (const auto& p : r.patches) {
      area += p.area_m2;
      p_max = std::max(p_max, p.p_max_Pa);
    }
    return std::pair{area, p_max};
  };
  const auto [area0, p_max0] = totals(*result);
  const Eigen::VectorXd base_gap = np->gap_m;
  std::vector<double> kappa;
  for (int b : kept_build) {
    const int wheel_sign = BodyCurvatureSign(cands[b].wheel_lateral_curvature);
    const int rail_sign = BodyCurvatureSign(cands[b].rail_lateral_curvature);
    kappa.push_back(CouplingCoefficient(problem.model.constants, problem.wheel_material,
                                        wheel_sign, problem.rail_material, rail_sign));
  }
  for (int it = 1; it <= o.coupling_max_iterations; ++it) {
    result->coupling_iterations = it;
    np->gap_m = base_gap;
    for (size_t k = 0; k < result->patches.size(); ++k) {
      const PatchResult& patch = result->patches[k];
      np->gap_m.segment(kept_offset[k], patch.grid.cells()) +=
          CouplingDisplacement(patch.grid, patch.rolling->tangential, kappa[k]);
    }
    const NormalSolution sol = SolveNormal(*np, problem.solver);
    result->iterations += sol.iterations;
    if (sol.status != SolverStatus::kConverged) {
      result->status = sol.status;
      result->message = "coupled normal solve: " + sol.message;
      return;
    }
    for (size_t k = 0; k < result->patches.size(); ++k) {
      PatchGrid grid = result->patches[k].grid;
      const int n = grid.cells();
      PatchResult updated =
          NumericalPatch(geom, std::move(grid), sol.pressure_Pa.segment(kept_offset[k], n));
      updated.model = std::move(result->patches[k].model);
      updated.model_reason = std::move(result->patches[k].model_reason);
      result->patches[k] = std::move(updated);
    }
    result->approach_m = sol.approach_m;
    if (o.longitudinal_force_N) {
      SolveRollingForForce(problem, geom, result);
    } else {
      SolveRolling(problem, geom, result);
    }
    const double change =
        (sol.pressure_Pa - pressure).cwiseAbs().maxCoeff() / std::max(pressure.maxCoeff(), 1.0);
    pressure = sol.pressure_Pa;
    if (change < o.coupling_tolerance) {
      const auto [area1, p_max1] = totals(*result);
      result->coupling_area_change = area1 / area0 - 1.0;
      result->coupling_p_max_change = p_max1 / p_max0 - 1.0;
      return;
    }
  }
  result->status = SolverStatus::kNotConverged;
  result->message = fmt::format("normal-tangential coupling did not settle in {} iterations",
                                o.coupling_max_iterations);
}

}  // namespace

std::optional<double> SolvePitchVelocityForForce(const std::function<double(double)>& fx,
                                                 double target_N, double speed_m_s,
                                                 double rolling_radius_m, double tolerance_N) {
  auto omega_of = [&](double c) { return -speed_m_s * (1.0 + c) / rolling_radius_m; };
  auto g = [&](double c) { return fx(omega_of(c)) - target_N; };
  // Bracket: step the creepage c outward from 0 (doubling) in the direction that moves fx toward
  // the target, until g changes sign.
  double a = 0.0, ga = g(0.0);
  if (std::abs(ga) <= tolerance_N) return omega_of(0.0);
  const double dir = ga < 0 ? 1.0 : -1.0;
  double b = a, gb = ga;
  for (double step = 1e-4;; step *= 2.0) {
    if (step > 1.0) return std::nullopt;  // beyond adhesion: the force never reaches the target
    b = dir * step;
    gb = g(b);
    if ((gb > 0) != (ga > 0)) break;
    a = b;
    ga = gb;
  }
  double lo = std::min(a, b), hi = std::max(a, b);
  double f_lo = lo == a ? ga : gb, f_hi = hi == a ? ga : gb;
  // Now f_lo < 0 < f_hi on [lo, hi]: bisection with secant (regula falsi, Illinois) steps.
  int side = 0;
  for (int it = 0; it < 200; ++it) {
    double c = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(c > lo && c < hi)) c = 0.5 * (lo + hi);
    const double f = g(c);
    if (std::abs(f) <= tolerance_N || hi - lo < 1e-14) return omega_of(c);
    if (f < 0) {
      lo = c;
      f_lo = f;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = c;
      f_hi = f;
      if (side == +1) f_lo *= 0.5;
      side = +1;
    }
  }
  return omega_of(0.5 * (lo + hi));
}

void ApplyRolling(const ContactProblem& problem, const WheelRailGeometry& geometry,
                  ContactResult* result) {
  RAILWEAR_CHECK(problem.rolling.has_value());
  SolveRolling(problem, geometry, result);
}

std::string_view ToString(TangentialMethod v) {
  return v == TangentialMethod::kFastsim ? "fastsim" : "exact";
}
std::optional<TangentialMethod> TangentialMethodFromString(std::string_view s) {
  if (s == "fastsim") return TangentialMethod::kFastsim;
  if (s == "exact") return TangentialMethod::kExact;
  return std::nullopt;
}

ContactResult SolveContact(const ContactProblem& problem) {
  const auto t_start = Clock::now();
  if (problem.load.vertical_force_N.has_value() == problem.load.approach_m.has_value()) {
    throw InputError("contact load: give exactly one of the vertical force and the approach");
  }
  if (!(problem.placement.rolling_radius_m > 0)) {
    throw InputError(fmt::format("wheel rolling radius = {} mm: expected a positive radius",
                                 problem.placement.rolling_radius_m * 1e3));
  }
  ContactResult result;
  result.model = problem.model;
  const std::string invalid = problem.solver.Validate();
  if (!invalid.empty()) throw InputError("normal solver options: " + invalid);

  auto t0 = Clock::now();
  const WheelPose pose{problem.placement.lateral_shift_m, problem.placement.roll_rad,
                       problem.placement.rolling_radius_m};
  const WheelRailGeometry geom(problem.wheel_profile, problem.rail_profile, pose);
  AddStage(&result.stages, "placement", SecondsSince(t0));
  auto finish = [&](ContactResult r) {
    r.time_s = SecondsSince(t_start);
    for (const auto& p : r.patches) {
      r.area_m2 += p.area_m2;
      r.p_max_Pa = std::max(r.p_max_Pa, p.p_max_Pa);
      r.vertical_force_N += p.vertical_force_N;
      r.lateral_force_N += p.lateral_force_N;
    }
    return r;
  };
  if (!geom.has_overlap()) {
    result.status = SolverStatus::kNoContact;
    result.message = "the wheel and rail profiles do not overlap laterally";
    return finish(result);
  }
  const bool load_given = problem.load.vertical_force_N.has_value();
  if ((load_given && !(*problem.load.vertical_force_N > 0)) ||
      (!load_given && !(*problem.load.approach_m > 0))) {
    result.status = SolverStatus::kNoContact;
    result.message = load_given ? "no load: the wheel only touches the rail"
                                : "no contact: the approach leaves the profiles apart";
    return finish(result);
  }

  if (problem.rolling && problem.model.kind == ModelKind::kHertz) {
    throw InputError(
        "rolling contact needs a patch grid: use the halfspace or conformal model, not hertz");
  }
  if (problem.rolling && problem.rolling->damage &&
      !(problem.rail_material.shear_yield_Pa > 0)) {
    throw InputError(
        "materials.rail.shear_yield_MPa is missing: expected the rail's shear yield stress k for "
        "the damage effect (FI_surf and the shakedown map need it)");
  }
  if (problem.rolling && !(problem.rolling->motion.speed_m_s > 0 && problem.rolling->friction > 0)) {
    throw InputError(fmt::format(
        "rolling contact: speed = {} m/s and friction = {}: expected both > 0",
        problem.rolling->motion.speed_m_s, problem.rolling->friction));
  }
  const double estar = ContactModulus(problem.wheel_material, problem.rail_material);
  if (problem.model.kind == ModelKind::kHertz) {
    const auto t_hertz = Clock::now();
    return finish(SolveHertzModel(SearchHertz(geom, problem, estar), std::move(result), t_hertz));
  }
  const double k_w = problem.wheel_material.Compliance();
  const double k_r = problem.rail_material.Compliance();
  const double stiffness_ratio_K = k_r / (k_w + k_r);
  const bool auto_model = problem.model.kind == ModelKind::kAuto;
  // The auto model's choice per patch, found again by position (the candidate's interval).
  struct ChoiceMemory {
    double y_lo_m, y_hi_m;
    PatchModelChoice choice;
  };
  std::vector<ChoiceMemory> hertz_verdicts;  // of the Hertz check, per Hertz patch
  // Hertz estimate of the approach and of the patch size at the first contact point.
  // (Widen the search when no gap sample lies within 1 um of first contact, e.g. at a corner.)
  std::vector<ContactCandidate> first = geom.FindCandidates(1e-6);
  for (double t = 1e-5; first.empty() && t < 1e-2; t *= 10) first = geom.FindCandidates(t);
  double delta_est = load_given
                         ? HertzApproachForLoad(first, problem.placement.roll_rad, estar,
                                                *problem.load.vertical_force_N)
                         : *problem.load.approach_m;
  std::vector<HertzSolution> hs;
  HertzVerticalLoad(first, problem.placement.roll_rad, estar, delta_est, &hs);
  double ax = 0.0, bs = 0.0;
  for (const auto& h : hs) {
    ax = std::max(ax, h.semi_axis_x_m);
    bs = std::max(bs, h.semi_axis_y_m);
  }
  // In nearly conformal contact Hertz's lateral semi-axis is far too large; bound it by the
  // lateral reach of the interpenetration at the estimated approach.
  const std::vector<ContactCandidate> at_delta_est = geom.FindCandidates(delta_est);
  {
    double reach = 0.0;
    for (const auto& c : at_delta_est) {
      reach = std::max(reach, 0.5 * (c.y_hi_m - c.y_lo_m) / std::max(-c.normal.y(), 0.1));
    }
    if (reach > 0) bs = std::min(bs, reach / std::sqrt(2.0));
  }
  if (auto_model && !problem.rolling) {
    // Hertz when every patch qualifies for it (Hertz and grid patches are not mixed in one
    // solve: they would need one common approach). Checked on the patches at the first contact
    // point first (the usual verdict, at no extra search), then on all Hertz's patches.
    t0 = Clock::now();
    auto verdicts = [&](const std::vector<ContactCandidate>& cands,
                        const std::vector<HertzSolution>& hertz, double delta,
                        const std::vector<ContactCandidate>& at_delta) {
      std::vector<ChoiceMemory> out;
      for (size_t k = 0; k < cands.size(); ++k) {
        if (hertz[k].force_N <= 0) continue;
        const ContactCandidate& c = cands[k];
        // The larger estimate of the patch: Hertz gets no check on a solved patch.
        const double b = EstimateSemiAxisS(geom, c, estar, delta, at_delta).hi;
        out.push_back({c.y_lo_m, c.y_hi_m,
                       ChoosePatchModel(MeasureConformity(geom, c, -b, b, stiffness_ratio_K),
                                        problem.model, "")});
      }
      return out;
    };
    auto all_hertz = [](const std::vector<ChoiceMemory>& v) {
      return !v.empty() && std::all_of(v.begin(), v.end(), [](const ChoiceMemory& m) {
        return m.choice.model == PatchModel::kHertz;
      });
    };
    hertz_verdicts = verdicts(first, hs, delta_est, at_delta_est);
    if (all_hertz(hertz_verdicts)) {
      const HertzSearch search = SearchHertz(geom, problem, estar);
      hertz_verdicts =
          verdicts(search.cands, search.hs, search.delta, geom.FindCandidates(search.delta));
      AddStage(&result.stages, "model selection", SecondsSince(t0));
      if (all_hertz(hertz_verdicts)) {
        ContactResult r = SolveHertzModel(search, std::move(result), Clock::now());
        RAILWEAR_CHECK(r.patches.size() == hertz_verdicts.size());
        for (size_t k = 0; k < r.patches.size(); ++k) {
          r.patches[k].model_reason = hertz_verdicts[k].choice.reason;
        }
        return finish(std::move(r));
      }
    } else {
      AddStage(&result.stages, "model selection", SecondsSince(t0));
    }
  }
  // Floors keep a degenerate estimate (no Hertz solution, a zero approach) from producing an
  // empty grid; the re-gridding below corrects the cell size from the first solution.
  constexpr double kMinSemiAxis_m = 1e-5, kMinThreshold_m = 1e-8;
  // Initial overlap a cell may show from the first-contact search's tolerance and the gap
  // projections' rounding (both ~1e-10 m) before it counts as a failed gap computation.
  constexpr double kMaxInitialOverlap_m = 1e-7;
  // Re-gridding never makes a patch finer than this many cells across its potential area (the
  // fine preset's patches need about 250).
  constexpr double kMaxCellsAlong = 300.0;
  // Patches carrying at least this share of the load get the preset's cells per semi-axis.
  constexpr double kFullShare = 0.1;
  // ... and at most kMaxCellsAlong scaled alike, but never fewer than this many across.
  constexpr double kMinCellsAlong = 40.0;
  // Memory one patch's influence operator may take (the curved one holds about 2 nx ns^2
  // doubles with its preconditioner, the planar one a few FFT buffers of the padded grid).
  constexpr double kMaxOperatorBytes = 4e9;
  CellSize cell = ChooseCellSize(problem.model, std::max(ax, kMinSemiAxis_m),
                                 std::max(bs, kMinSemiAxis_m));
  double threshold = std::max(2.0 * delta_est, kMinThreshold_m);

  InfluenceSettings settings{problem.model.kernel, problem.model.constants,
                             problem.wheel_material, problem.rail_material};
  const double n_per_axis = CellsPerSemiAxis(problem.model.accuracy);
  const bool cell_fixed = problem.model.cell_dx_m.has_value() || problem.model.cell_ds_m.has_value();

  // Each patch keeps its own cell size once it has been measured (two-point contact: a small
  // flange patch must not shrink the cells of a large tread patch), found again by position.
  struct CellMemory {
    double y_lo_m, y_hi_m;
    CellSize cell;
  };
  std::vector<CellMemory> cell_memory;
  // The auto model's choice per patch: made from the estimated patch when it first appears,
  // checked again on each solution while it is planar (the estimate can miss a patch that
  // spreads), and then only ever switched to the conformal geometry.
  std::vector<ChoiceMemory> choice_memory;
  // Why a grid patch is not Hertz (Hertz and grid patches are not mixed in one solve).
  auto no_hertz_reason = [&](const ContactCandidate& c) -> std::string {
    if (problem.rolling) return "rolling contact needs a grid";
    for (const auto& v : hertz_verdicts) {
      if (c.y_m < v.y_lo_m || c.y_m > v.y_hi_m) continue;
      if (v.choice.model == PatchModel::kHertz) {
        return "Hertz would do here, but another patch needs a grid";
      }
      if (v.choice.model == PatchModel::kConformal) {
        return "on the larger estimate of the patch the Hertz check found it conformal";
      }
      const std::string& r = v.choice.reason;
      const size_t at = r.find("not Hertz: ");
      return r.substr(at == std::string::npos ? 0 : at + 11) +
             " (on the larger estimate of the patch)";
    }
    return "the patch appeared after the Hertz check";
  };
  PatchModelChoice fixed_choice;  // the scene's model for every patch when it is not auto
  fixed_choice.geometry = problem.model.geometry;
  fixed_choice.kernel = problem.model.kernel;
  fixed_choice.label = PatchModelLabel(problem.model);
  double approach_now = delta_est;  // the best estimate of the approach so far
  std::vector<ContactCandidate> at_approach = at_delta_est;  // FindCandidates(approach_now)
  double at_approach_delta = delta_est;
  int regrids = 0, total_iterations = 0;
  // Grids are cropped to the cells an approach of trim_approach could close (patch_builder.h):
  // unbounded until a solve has measured the approach, then kTrimFactor times the last one.
  constexpr double kTrimFactor = 1.2;
  double trim_approach = std::numeric_limits<double>::infinity();
  for (int attempt = 0; attempt < 12; ++attempt) {
    t0 = Clock::now();
    const std::vector<ContactCandidate> cands = geom.FindCandidates(threshold);
    std::vector<PatchBuild> builds;
    std::vector<CellMemory> build_cells;
    std::vector<ContactCandidate> build_cands;
    std::vector<PatchModelChoice> build_choices;
    for (const auto& c : cands) {
      CellSize cc = cell;
      for (const auto& m : cell_memory) {
        if (c.y_m >= m.y_lo_m && c.y_m <= m.y_hi_m) cc = m.cell;
      }
      PatchModelChoice choice = fixed_choice;
      if (auto_model) {
        const ChoiceMemory* known = nullptr;
        for (const auto& m : choice_memory) {
          if (c.y_m >= m.y_lo_m && c.y_m <= m.y_hi_m) known = &m;
        }
        if (known != nullptr) {
          choice = known->choice;
        } else {
          if (approach_now != at_approach_delta) {
            at_approach = geom.FindCandidates(approach_now);
            at_approach_delta = approach_now;
          }
          const double b = EstimateSemiAxisS(geom, c, estar, approach_now, at_approach).lo;
          choice = ChoosePatchModel(MeasureConformity(geom, c, -b, b, stiffness_ratio_K),
                                    problem.model, no_hertz_reason(c));
          choice_memory.push_back({c.y_lo_m, c.y_hi_m, choice});
        }
      }
      PatchGridOptions o;
      o.geometry = choice.geometry;
      o.cell_dx_m = cc.dx_m;
      o.cell_ds_m = cc.ds_m;
      o.threshold_m = threshold;
      o.stiffness_ratio_K = stiffness_ratio_K;
      o.trim_approach_m = trim_approach;
      o.max_operator_bytes = kMaxOperatorBytes;
      PatchBuild b = BuildPatchGrid(geom, c, o);
      if (b.too_large) {
        // A status, not std::bad_alloc, when a grid outgrows memory (the cell rules of the
        // re-gridding below keep within it; an explicit cell_mm may not).
        result.status = SolverStatus::kNotConverged;
        result.message = fmt::format(
            "the potential contact area needs a {} x {} grid, whose influence operator would "
            "take {:.1f} GB (at most {:.0f} GB): choose a coarser accuracy or larger cell_mm",
            b.grid.nx, b.grid.ns,
            EstimateOperatorBytes(b.grid.nx, b.grid.ns, b.grid.planar) / 1e9,
            kMaxOperatorBytes / 1e9);
        return finish(result);
      }
      if (b.valid) {
        builds.push_back(std::move(b));
        build_cells.push_back({c.y_lo_m, c.y_hi_m, cc});
        build_cands.push_back(c);
        build_choices.push_back(std::move(choice));
      }
    }
    AddStage(&result.stages, "grid", SecondsSince(t0));
    if (builds.empty()) {
      result.status = SolverStatus::kNoContact;
      result.message = "no usable contact patch (surfaces too steep for a vertical approach)";
      return finish(result);
    }
    for (const PatchBuild& b : builds) {
      // The wheel was lowered to first contact, so no cell may start inside the rail: a
      // negative initial separation is a geometry failure (a projection that found the wrong
      // branch), and a solve on it "converges" to nonsense (a lifted wheel on a few cells).
      if (const double g = b.grid.gap_m.minCoeff(); g < -kMaxInitialOverlap_m) {
        result.status = SolverStatus::kNotConverged;
        result.message = fmt::format(
            "the initial separation is negative ({:.4g} um) in a cell of the potential contact "
            "area: the gap computation failed there; try the other geometry model",
            g * 1e6);
        return finish(result);
      }
    }

    t0 = Clock::now();
    std::vector<std::unique_ptr<InfluenceOperator>> ops;
    NormalProblem np;
    int total = 0;
    for (const auto& b : builds) total += b.grid.cells();
    np.gap_m.resize(total);
    np.approach_weight.resize(total);
    np.cell_area_m2.resize(total);
    int offset = 0;
    for (size_t k = 0; k < builds.size(); ++k) {
      const PatchBuild& b = builds[k];
      InfluenceSettings patch_settings = settings;
      patch_settings.kernel = build_choices[k].kernel;
      patch_settings.wheel_curvature_sign =
          BodyCurvatureSign(build_cands[k].wheel_lateral_curvature);
      patch_settings.rail_curvature_sign = BodyCurvatureSign(build_cands[k].rail_lateral_curvature);
      ops.push_back(MakeInfluenceOperator(b.grid, patch_settings));
      np.blocks.push_back(ops.back().get());
      np.gap_m.segment(offset, b.grid.cells()) = b.grid.gap_m;
      for (int j = 0; j < b.grid.ns; ++j) {
        const double w = -b.grid.normal_yz[j].y();
        np.approach_weight.segment(offset + j * b.grid.nx, b.grid.nx).setConstant(w);
      }
      np.cell_area_m2.segment(offset, b.grid.cells()).setConstant(b.grid.CellArea());
      offset += b.grid.cells();
    }
    np.force_N = problem.load.vertical_force_N;
    np.approach_m = problem.load.approach_m;
    AddStage(&result.stages, "influence", SecondsSince(t0));

    t0 = Clock::now();
    const NormalSolution sol = SolveNormal(np, problem.solver);
    AddStage(&result.stages, "solve", SecondsSince(t0));
    total_iterations += sol.iterations;
    if (sol.status == SolverStatus::kConverged) approach_now = sol.approach_m;

    // Decide whether the grid fits the solution (and, for auto, whether a planar patch still
    // qualifies for the planar grid on its solved extent).
    bool grow = false, regrid = false, switched = false;
    std::vector<CellMemory> next_memory;
    const double total_load = sol.pressure_Pa.dot(np.cell_area_m2);
    offset = 0;
    for (size_t k = 0; k < builds.size(); ++k) {
      const PatchBuild& b = builds[k];
      CellMemory mem = build_cells[k];
      const auto p_k = sol.pressure_Pa.segment(offset, b.grid.cells());
      const Extent e = MeasureExtent(b.grid, p_k);
      const double share =
          total_load > 0.0 ? p_k.sum() * b.grid.CellArea() / total_load : 1.0;
      offset += b.grid.cells();
      if (e.cells == 0) continue;
      if (auto_model && build_choices[k].model != PatchModel::kConformal &&
          sol.status == SolverStatus::kConverged) {
        constexpr double kTiny_m = 1e-9;  // keeps the measured stretch around the contact point
        PatchConformity post =
            MeasureConformity(geom, build_cands[k], std::min(e.s_lo, -kTiny_m),
                              std::max(e.s_hi, kTiny_m), stiffness_ratio_K);
        post.measured = true;
        const PatchModelChoice again =
            ChoosePatchModel(post, problem.model, no_hertz_reason(build_cands[k]));
        for (auto& m : choice_memory) {
          if (build_cands[k].y_m >= m.y_lo_m && build_cands[k].y_m <= m.y_hi_m) m.choice = again;
        }
        build_choices[k] = again;
        switched = switched || again.model == PatchModel::kConformal;
      }
      if (e.touches_x_edge || (e.touches_s_edge && !b.lateral_limited)) grow = true;
      if (!cell_fixed && regrids < 3) {
        // The preset's cells per semi-axis for every patch that carries at least
        // kFullShare of the load. A patch that barely touches (a third candidate on a worn
        // rail: 0.03 mm2 beside 126 mm2) would otherwise be re-gridded into millions of tiny
        // cells over its potential area, and the curved operator's nx ns^2 memory with them;
        // its force error is its share times its relative error, so it keeps
        // n sqrt(share / kFullShare) cells per semi-axis (at least the draft preset's), and
        // never more than kMaxCellsAlong (scaled alike, at least kMinCellsAlong) across its
        // potential area.
        const double weight = std::sqrt(std::min(1.0, share / kFullShare));
        const double n_patch =
            std::max(CellsPerSemiAxis(AccuracyPreset::kDraft), n_per_axis * weight);
        const double along = std::max(kMinCellsAlong, kMaxCellsAlong * weight);
        const CellSize target{std::max(e.half_x / n_patch, b.grid.nx * b.grid.dx_m / along),
                              std::max(e.half_s / n_patch, b.grid.ns * b.grid.ds_m / along)};
        if (std::abs(target.dx_m / mem.cell.dx_m - 1.0) > 0.3 ||
            std::abs(target.ds_m / mem.cell.ds_m - 1.0) > 0.3) {
          regrid = true;
          mem.cell = target;
        }
      }
      next_memory.push_back(mem);
    }
    cell_memory = std::move(next_memory);
    const bool more_candidates = sol.status == SolverStatus::kConverged &&
                                 sol.approach_m > 0.7 * threshold;
    // The crop is exact only while the approach stays below the one it was made for.
    const bool outgrew_trim = sol.status == SolverStatus::kConverged && sol.approach_m > trim_approach;
    if (sol.status == SolverStatus::kConverged) trim_approach = kTrimFactor * sol.approach_m;
    if (sol.status == SolverStatus::kConverged &&
        (grow || regrid || more_candidates || switched || outgrew_trim) && attempt < 11) {
      if (grow) threshold *= 1.8;
      if (more_candidates) threshold = std::max(threshold, 2.0 * sol.approach_m);
      if (regrid) {
        ++regrids;
        threshold = std::max(threshold, 2.0 * sol.approach_m);
      }
      continue;
    }

    result.status = sol.status;
    result.message = sol.message;
    result.approach_m = sol.approach_m;
    result.iterations = total_iterations;
    offset = 0;
    std::vector<int> kept_build, kept_offset;  // build index and vector offset of each patch
    for (size_t k = 0; k < builds.size(); ++k) {
      const int n = builds[k].grid.cells();
      PatchResult pr =
          NumericalPatch(geom, std::move(builds[k].grid), sol.pressure_Pa.segment(offset, n));
      if (pr.cells_in_contact > 0) {
        pr.model = build_choices[k].label;
        if (auto_model) pr.model_reason = build_choices[k].reason;
        result.patches.push_back(std::move(pr));
        kept_build.push_back(static_cast<int>(k));
        kept_offset.push_back(offset);
      }
      offset += n;
    }
    if (grow) {
      result.message += (result.message.empty() ? "" : "; ");
      result.message += "pressure reaches the edge of the potential contact area";
    }
    if (problem.rolling && result.status == SolverStatus::kConverged) {
      t0 = Clock::now();
      if (problem.rolling->longitudinal_force_N) {
        SolveRollingForForce(problem, geom, &result);
      } else {
        SolveRolling(problem, geom, &result);
      }
      AddStage(&result.stages, "tangential", SecondsSince(t0));
      if (problem.rolling->coupling) {
        t0 = Clock::now();
        SolveCoupled(problem, geom, build_cands, kept_build, kept_offset, &np, sol.pressure_Pa,
                     &result);
        AddStage(&result.stages, "coupling", SecondsSince(t0));
      }
    }
    return finish(result);
  }
  result.status = SolverStatus::kNotConverged;
  result.message = "the potential contact area did not settle";
  return finish(result);
}

}  // namespace railwear
