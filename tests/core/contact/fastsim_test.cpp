// Tests of fastsim.h: Kalker's linear theory at small creepage, full slip at large creepage,
// the reference README §4 FASTSIM check, mirror symmetry.
#include "core/contact/fastsim.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/contact/kalker_coefficients.h"
#include "tests/core/contact/hertz_grid.h"

namespace railwear {
namespace {

// The README §4 case: a = 8, b = 4 mm, Fn = 82 kN, G = 82 000 MPa, nu = 0.28, mu = 0.3.
constexpr double kA = 8e-3, kB = 4e-3, kFn = 82e3, kG = 82e9, kNu = 0.28, kMu = 0.3;
// The "must show" (a): FASTSIM with Kalker's flexibilities reproduces linear theory in
// the continuum limit; on an 80 x 80 grid the discretisation of the strip ends costs < 2 %.
constexpr double kLinearRelTol = 0.02;
// (b): in full slip every cell carries mu p, so |F_t| = mu Fn up to round-off; 0.1 % is the
// issue's bound.
constexpr double kFullSlipRelTol = 1e-3;
// (c): the README's reference values are CONTACT's FASTSIM results for its example
// examples/fastsim.inp (cases 2 and 3: M=3, 40 x 40 cells in the contact, first-order march,
// blended flexibilities; see fastsim.h). The same discretisation here reproduces them; the
// issue asks for 1 %.
constexpr double kCheckRelTol = 0.01;
// CONTACT's grid of that example: 44 x 44 cells over SCALE = 1.1 times the Hertz rectangle.
constexpr int kContactCells = 44;
constexpr double kContactScale = 1.1;
// The continuum limit of the simplified theory: the second-order march on 200 x 200 and on
// 400 x 400 cells agree to better than this (measured 0.1 %; cells cut by the ellipse edge).
constexpr double kConvergedRelTol = 3e-3;
// First-order convergence of CONTACT's march: doubling the cells halves its error against the
// continuum (measured ratio printed); the bounds leave room for the irregular edge cells.
constexpr double kFirstOrderRatioMin = 1.6, kFirstOrderRatioMax = 2.5;

// Planar grid of nx x ns cells exactly covering scale * [-a, a] x [-b, b] with the Hertz
// pressure p0 sqrt(1 - x^2/a^2 - s^2/b^2), p0 = 3 Fn/(2 pi a b).
struct HertzPatch {
  PatchGrid grid;
  Eigen::VectorXd pressure_Pa;
  double fn_N = 0.0;  // sum p dA (the discrete normal force)
};

HertzPatch MakeHertzPatch(int nx, int ns, double a = kA, double b = kB, double fn = kFn,
                          double scale = 1.0) {
  HertzPatch h;
  h.grid = testing::MakeHertzGrid(scale * a, scale * b, nx, ns);
  const PatchGrid& g = h.grid;
  const double p0 = 3.0 * fn / (2.0 * std::numbers::pi * a * b);
  h.pressure_Pa = Eigen::VectorXd::Zero(g.cells());
  for (int j = 0; j < ns; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double r = 1.0 - std::pow(g.X(i) / a, 2) - std::pow(g.S(j) / b, 2);
      h.pressure_Pa[g.Index(i, j)] = r > 0.0 ? p0 * std::sqrt(r) : 0.0;
    }
  }
  h.fn_N = h.pressure_Pa.sum() * g.CellArea();
  return h;
}

// Kalker's planar creepage field w_x = xi - phi s, w_s = eta + phi x.
RollingInput MakeCreepage(const PatchGrid& g, double xi, double eta, double phi) {
  return testing::KalkerCreepage(g, xi, eta, phi, 10.0, kMu);
}

FastsimOptions MakeOptions() {
  FastsimOptions o;
  o.shear_modulus_Pa = kG;
  o.poisson_ratio = kNu;
  return o;
}

TEST(Fastsim, SmallCreepageMatchesLinearTheory) {
  const HertzPatch h = MakeHertzPatch(80, 80);
  struct Case {
    const char* name;
    double xi, eta, phi;
  };
  // Creepages 1e-6 (spin 1e-4 /m): the stick zone covers all but the trailing edge cells.
  const Case cases[] = {{"xi", 1e-6, 0.0, 0.0},
                        {"eta", 0.0, 1e-6, 0.0},
                        {"spin", 0.0, 0.0, 1e-4},
                        {"-xi", -1e-6, 0.0, 0.0},
                        {"mix", 1e-6, -1e-6, 1e-4}};
  for (FlexibilityModel model : {FlexibilityModel::kThree, FlexibilityModel::kWeighted}) {
    for (const Case& c : cases) {
      // The single weighted flexibility is exact for each pure creepage only (fastsim.h).
      if (model == FlexibilityModel::kWeighted && std::string(c.name) == "mix") continue;
      for (bool given_axes : {true, false}) {
        FastsimOptions o = MakeOptions();
        o.flexibility = model;
        if (given_axes) {
          o.semi_axis_x_m = kA;
          o.semi_axis_s_m = kB;
        }
        const RollingInput in = MakeCreepage(h.grid, c.xi, c.eta, c.phi);
        const TangentialSolution sol = SolveFastsim(h.grid, h.pressure_Pa, in, o);
        ASSERT_EQ(sol.status, SolverStatus::kConverged);
        const LinearCreepForces lin = CalcLinearCreepForces(kA, kB, kG, kNu, c.xi, c.eta, c.phi);
        const double ref = std::hypot(lin.force_x_N, lin.force_y_N);
        EXPECT_NEAR(sol.force_x_N, lin.force_x_N, kLinearRelTol * ref) << c.name << given_axes;
        EXPECT_NEAR(sol.force_s_N, lin.force_y_N, kLinearRelTol * ref) << c.name << given_axes;
        const double err =
            std::hypot(sol.force_x_N - lin.force_x_N, sol.force_s_N - lin.force_y_N) / ref;
        std::printf(
            "linear %-8s %-5s axes %s: Fx %.6g (lin %.6g)  Fy %.6g (lin %.6g)  err %.3g%%\n",
            std::string(ToString(model)).c_str(), c.name, given_axes ? "given" : "estim",
            sol.force_x_N, lin.force_x_N, sol.force_s_N, lin.force_y_N, 100.0 * err);
      }
    }
  }
}

TEST(Fastsim, LargeCreepageSaturatesAtCoulomb) {
  const HertzPatch h = MakeHertzPatch(70, 80);
  for (TractionBound bound : {TractionBound::kActualPressure, TractionBound::kParabolic}) {
    for (FastsimMarch march : {FastsimMarch::kTrapezoidal, FastsimMarch::kContactEuler}) {
      FastsimOptions o = MakeOptions();
      o.bound = bound;
      o.march = march;
      const RollingInput in = MakeCreepage(h.grid, 0.3, -0.4, 0.0);
      const TangentialSolution sol = SolveFastsim(h.grid, h.pressure_Pa, in, o);
      const double ft = std::hypot(sol.force_x_N, sol.force_s_N);
      EXPECT_NEAR(ft, kMu * h.fn_N, kFullSlipRelTol * kMu * h.fn_N)
          << ToString(bound) << " " << ToString(march);
      EXPECT_LT(sol.force_x_N, 0.0);  // opposes xi > 0
      EXPECT_GT(sol.force_s_N, 0.0);  // opposes eta < 0
      EXPECT_EQ(sol.stick_area_m2, 0.0);
      for (int k = 0; k < h.grid.cells(); ++k) {
        const double q = std::hypot(sol.traction_x_Pa[k], sol.traction_s_Pa[k]);
        if (h.pressure_Pa[k] <= 0.0) {
          EXPECT_EQ(q, 0.0);
          EXPECT_EQ(sol.stick[k], -1);
        } else if (bound == TractionBound::kActualPressure) {
          EXPECT_LE(q, kMu * h.pressure_Pa[k] * (1.0 + 1e-12));
          EXPECT_EQ(sol.stick[k], 0);
        }
      }
      // Frictional power in full slip: every cell slides at about V |w|.
      EXPECT_GT(sol.frictional_power_W, 0.0);
    }
  }
}

TEST(Fastsim, TractionBoundAndSlipDirection) {
  // Partial slip with spin: |q| <= mu p everywhere and the slip opposes the traction.
  const HertzPatch h = MakeHertzPatch(70, 80);
  const RollingInput in = MakeCreepage(h.grid, 3e-4, -6.25e-4, 0.625);
  const TangentialSolution sol = SolveFastsim(h.grid, h.pressure_Pa, in, MakeOptions());
  EXPECT_GT(sol.stick_area_m2, 0.0);
  EXPECT_GT(sol.slip_area_m2, 0.0);
  for (int k = 0; k < h.grid.cells(); ++k) {
    const double qx = sol.traction_x_Pa[k], qs = sol.traction_s_Pa[k];
    EXPECT_LE(std::hypot(qx, qs), kMu * h.pressure_Pa[k] * (1.0 + 1e-12));
    if (sol.stick[k] == 0) {
      const double v = std::hypot(sol.slip_x_m_s[k], sol.slip_s_m_s[k]);
      const double q = std::hypot(qx, qs);
      if (v > 0.0 && q > 0.0) {
        EXPECT_NEAR((qx * sol.slip_x_m_s[k] + qs * sol.slip_s_m_s[k]) / (q * v), -1.0, 1e-12);
      }
    } else if (sol.stick[k] == 1) {
      EXPECT_EQ(sol.slip_x_m_s[k], 0.0);
      EXPECT_EQ(sol.slip_s_m_s[k], 0.0);
    }
  }
}

// Fy/(mu Fn) of the README check case: xi = 0, eta = -6.25e-4, phi = +6.25e-4 /mm.
double CheckCaseRatio(const HertzPatch& h, const FastsimOptions& o) {
  const RollingInput in = MakeCreepage(h.grid, 0.0, -6.25e-4, 0.625);
  const TangentialSolution sol = SolveFastsim(h.grid, h.pressure_Pa, in, o);
  EXPECT_EQ(sol.status, SolverStatus::kConverged);
  return sol.force_s_N / (kMu * h.fn_N);
}

TEST(Fastsim, ReadmeCheckCaseOnContactsDiscretisation) {
  // Reference README §4: Fy/(mu Fn) = -0.6118 (parabolic bound) and -0.6016 (elliptic bound),
  // CONTACT's FASTSIM on its 40 x 40-cell example (fastsim.h).
  const HertzPatch h = MakeHertzPatch(kContactCells, kContactCells, kA, kB, kFn, kContactScale);
  struct Case {
    TractionBound bound;
    double expected;
  };
  for (const Case& c :
       {Case{TractionBound::kParabolic, -0.6118}, Case{TractionBound::kActualPressure, -0.6016}}) {
    FastsimOptions o = MakeOptions();
    o.bound = c.bound;
    o.march = FastsimMarch::kContactEuler;
    o.blend_flexibilities = true;
    o.semi_axis_x_m = kA;  // CONTACT takes a, b from its Hertz input
    o.semi_axis_s_m = kB;
    FastsimPatch patch;
    const RollingInput in = MakeCreepage(h.grid, 0.0, -6.25e-4, 0.625);
    const TangentialSolution sol = SolveFastsim(h.grid, h.pressure_Pa, in, o, &patch);
    const double ratio = sol.force_s_N / (kMu * h.fn_N);
    std::printf(
        "README check, CONTACT discretisation, %s bound: Fy/(mu Fn) = %.4f (reference "
        "%.4f, %+.2f %%), blend weight %.4f\n",
        std::string(ToString(c.bound)).c_str(), ratio, c.expected,
        100.0 * (ratio / c.expected - 1.0), patch.blend_weight);
    EXPECT_NEAR(ratio, c.expected, kCheckRelTol * std::abs(c.expected)) << ToString(c.bound);
    EXPECT_GT(patch.blend_weight, 0.0);
    EXPECT_LT(patch.blend_weight, 1.0);
  }
}

TEST(Fastsim, ReadmeCheckCaseConvergence) {
  // Why the reference figures are not the simplified theory's continuum values: the second-order
  // march converges (200 vs 400 cells per axis), and CONTACT's first-order march (unblended,
  // same flexibilities) approaches that limit with an error halving with the cell size.
  for (TractionBound bound : {TractionBound::kParabolic, TractionBound::kActualPressure}) {
    FastsimOptions o = MakeOptions();
    o.bound = bound;
    o.semi_axis_x_m = kA;
    o.semi_axis_s_m = kB;
    const double r200 = CheckCaseRatio(MakeHertzPatch(200, 200), o);
    const double r400 = CheckCaseRatio(MakeHertzPatch(400, 400), o);
    EXPECT_NEAR(r200, r400, kConvergedRelTol * std::abs(r400)) << ToString(bound);
    o.march = FastsimMarch::kContactEuler;
    const double e40 =
        CheckCaseRatio(MakeHertzPatch(kContactCells, kContactCells, kA, kB, kFn, kContactScale),
                       o) -
        r400;
    const double e80 =
        CheckCaseRatio(
            MakeHertzPatch(2 * kContactCells, 2 * kContactCells, kA, kB, kFn, kContactScale), o) -
        r400;
    std::printf(
        "%s bound: continuum %.4f (200: %.4f), first-order march error %.4f on 40 "
        "cells, %.4f on 80 (ratio %.2f)\n",
        std::string(ToString(bound)).c_str(), r400, r200, e40, e80, e40 / e80);
    if (bound == TractionBound::kParabolic) {
      // The parabolic case is where the reference differs: its 40-cell error is several %.
      EXPECT_GT(e40 / e80, kFirstOrderRatioMin);
      EXPECT_LT(e40 / e80, kFirstOrderRatioMax);
      EXPECT_GT(std::abs(e40), 0.03 * std::abs(r400));
    }
  }
}

TEST(Fastsim, MirroredCreepageMirrorsForces) {
  // Mirroring s -> -s maps (xi, eta, phi) to (xi, -eta, -phi) and (Fx, Fy, Mz) to (Fx, -Fy, -Mz);
  // reversing all creepages reverses all forces.
  const HertzPatch h = MakeHertzPatch(60, 60);
  const FastsimOptions o = MakeOptions();
  const TangentialSolution s0 =
      SolveFastsim(h.grid, h.pressure_Pa, MakeCreepage(h.grid, 2e-4, -5e-4, 0.4), o);
  const TangentialSolution s1 =
      SolveFastsim(h.grid, h.pressure_Pa, MakeCreepage(h.grid, 2e-4, 5e-4, -0.4), o);
  const TangentialSolution s2 =
      SolveFastsim(h.grid, h.pressure_Pa, MakeCreepage(h.grid, -2e-4, 5e-4, -0.4), o);
  const double scale = kMu * h.fn_N;
  constexpr double kRoundOff = 1e-12;  // same arithmetic on mirrored data
  EXPECT_NEAR(s1.force_x_N, s0.force_x_N, kRoundOff * scale);
  EXPECT_NEAR(s1.force_s_N, -s0.force_s_N, kRoundOff * scale);
  EXPECT_NEAR(s1.spin_moment_Nm, -s0.spin_moment_Nm, kRoundOff * scale * kA);
  EXPECT_NEAR(s2.force_x_N, -s0.force_x_N, kRoundOff * scale);
  EXPECT_NEAR(s2.force_s_N, -s0.force_s_N, kRoundOff * scale);
  EXPECT_NEAR(s1.stick_area_m2, s0.stick_area_m2, 1e-18);
}

TEST(Fastsim, SeparateFlexibilitiesMatchLinearTheoryForXiAndEta) {
  const HertzPatch h = MakeHertzPatch(80, 80);
  FastsimOptions o = MakeOptions();
  o.flexibility = FlexibilityModel::kSeparate;
  const RollingInput in = MakeCreepage(h.grid, 1e-6, 2e-6, 0.0);
  const TangentialSolution sol = SolveFastsim(h.grid, h.pressure_Pa, in, o);
  const LinearCreepForces lin = CalcLinearCreepForces(kA, kB, kG, kNu, 1e-6, 2e-6, 0.0);
  EXPECT_NEAR(sol.force_x_N, lin.force_x_N, kLinearRelTol * std::abs(lin.force_x_N));
  EXPECT_NEAR(sol.force_s_N, lin.force_y_N, kLinearRelTol * std::abs(lin.force_y_N));
}

TEST(Fastsim, FitsPatchAverageCreepages) {
  const HertzPatch h = MakeHertzPatch(40, 40);
  FastsimPatch patch;
  SolveFastsim(h.grid, h.pressure_Pa, MakeCreepage(h.grid, 1e-4, -2e-4, 0.3), MakeOptions(),
               &patch);
  EXPECT_NEAR(patch.xi, 1e-4, 1e-15);
  EXPECT_NEAR(patch.eta, -2e-4, 1e-15);
  EXPECT_NEAR(patch.phi_per_m, 0.3, 1e-12);
}

TEST(Fastsim, NoContactAndBadInput) {
  HertzPatch h = MakeHertzPatch(10, 10);
  const RollingInput in = MakeCreepage(h.grid, 1e-3, 0.0, 0.0);
  const TangentialSolution none =
      SolveFastsim(h.grid, Eigen::VectorXd::Zero(h.grid.cells()), in, MakeOptions());
  EXPECT_EQ(none.status, SolverStatus::kNoContact);
  EXPECT_EQ(none.force_x_N, 0.0);
  RollingInput bad = in;
  bad.friction = -0.1;
  try {
    SolveFastsim(h.grid, h.pressure_Pa, bad, MakeOptions());
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("friction = -0.1"), std::string::npos) << e.what();
  }
  FastsimOptions o = MakeOptions();
  o.poisson_ratio = 0.7;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("poisson_ratio = 0.7"), std::string::npos) << error;
  FastsimOptions blend = MakeOptions();
  blend.blend_flexibilities = true;
  blend.flexibility = FlexibilityModel::kWeighted;
  EXPECT_FALSE(blend.IsValid(&error));
  EXPECT_NE(error.find("blend_flexibilities needs flexibility = three, got weighted"),
            std::string::npos)
      << error;
  EXPECT_THROW(SolveFastsim(h.grid, Eigen::VectorXd::Zero(3), in, MakeOptions()),
               std::invalid_argument);
}

TEST(Fastsim, MarchNamesRoundTrip) {
  for (FastsimMarch m : {FastsimMarch::kTrapezoidal, FastsimMarch::kContactEuler}) {
    EXPECT_EQ(FastsimMarchFromString(ToString(m)), m);
  }
  EXPECT_FALSE(FastsimMarchFromString("euler").has_value());
}

}  // namespace
}  // namespace railwear
