// Bit-for-bit comparison of two contact results, for the tests of exact reuse (a kept placement,
// a kept normal part): every number of a wheel's result that the C API reports, and the
// solver's counts and residuals, compared with ==. ExpectSameNormal and ExpectSameTangential do
// the same for one solver's result (a reused operator or solver setup).
#pragma once

#include <gtest/gtest.h>

#include "core/contact/contact_result.h"
#include "core/contact/normal_solver.h"
#include "core/contact/tangential_types.h"

namespace railwear::testing {

inline void ExpectSameResult(const ContactResult& a, const ContactResult& b) {
  ASSERT_EQ(a.status, b.status);
  ASSERT_EQ(a.patches.size(), b.patches.size());
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.approach_m, b.approach_m);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.vertical_force_N, b.vertical_force_N);
  EXPECT_EQ(a.lateral_force_N, b.lateral_force_N);
  EXPECT_EQ(a.pitch_velocity_rad_s, b.pitch_velocity_rad_s);
  EXPECT_EQ(a.balance_iterations, b.balance_iterations);
  EXPECT_EQ(a.balance_residual, b.balance_residual);
  for (size_t k = 0; k < a.patches.size(); ++k) {
    const PatchResult& p = a.patches[k];
    const PatchResult& q = b.patches[k];
    EXPECT_EQ(p.area_m2, q.area_m2);
    EXPECT_EQ(p.p_max_Pa, q.p_max_Pa);
    EXPECT_EQ(p.contact_x_m, q.contact_x_m);
    EXPECT_EQ(p.contact_point_yz_m, q.contact_point_yz_m);
    EXPECT_EQ(p.pressure_Pa, q.pressure_Pa);
    ASSERT_EQ(p.rolling.has_value(), q.rolling.has_value());
    if (p.rolling) {
      EXPECT_EQ(p.rolling->creepage.xi, q.rolling->creepage.xi);
      EXPECT_EQ(p.rolling->creepage.eta, q.rolling->creepage.eta);
      EXPECT_EQ(p.rolling->tangential.force_x_N, q.rolling->tangential.force_x_N);
      EXPECT_EQ(p.rolling->tangential.force_s_N, q.rolling->tangential.force_s_N);
      EXPECT_EQ(p.rolling->tangential.traction_x_Pa, q.rolling->tangential.traction_x_Pa);
    }
  }
}

inline void ExpectSameNormal(const NormalSolution& a, const NormalSolution& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.pressure_Pa, b.pressure_Pa);
  EXPECT_EQ(a.deformed_gap_m, b.deformed_gap_m);
  EXPECT_EQ(a.approach_m, b.approach_m);
  EXPECT_EQ(a.force_N, b.force_N);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.complementarity_residual_m, b.complementarity_residual_m);
  EXPECT_EQ(a.load_error_relative, b.load_error_relative);
  EXPECT_EQ(a.operator_applications, b.operator_applications);
  EXPECT_EQ(a.preconditioner_applications, b.preconditioner_applications);
}

inline void ExpectSameTangential(const TangentialSolution& a, const TangentialSolution& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.traction_x_Pa, b.traction_x_Pa);
  EXPECT_EQ(a.traction_s_Pa, b.traction_s_Pa);
  EXPECT_EQ(a.slip_x_m_s, b.slip_x_m_s);
  EXPECT_EQ(a.slip_s_m_s, b.slip_s_m_s);
  EXPECT_EQ(a.stick, b.stick);
  EXPECT_EQ(a.force_x_N, b.force_x_N);
  EXPECT_EQ(a.force_s_N, b.force_s_N);
  EXPECT_EQ(a.force_s_yz_N, b.force_s_yz_N);
  EXPECT_EQ(a.spin_moment_Nm, b.spin_moment_Nm);
  EXPECT_EQ(a.stick_area_m2, b.stick_area_m2);
  EXPECT_EQ(a.slip_area_m2, b.slip_area_m2);
  EXPECT_EQ(a.frictional_power_W, b.frictional_power_W);
}

}  // namespace railwear::testing
