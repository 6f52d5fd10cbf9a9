// ABI: the header compiles as C99 (abi_c99.c) and as C++ (this file); the struct sizes are the
// same in both languages and equal the pinned ones, and the version numbers are pinned. A change
// of any of these is an ABI change: it needs a new major version (or a minor one when a struct
// only grows at its end and the library accepts both sizes) and this test updated with it.
#include <cstddef>
#include <cstring>

#include <gtest/gtest.h>

#include "railwear/railwear.h"

extern "C" size_t rw_test_c_sizeof(int which);
extern "C" double rw_test_c_solve(void);

namespace {

TEST(ApiAbi, VersionNumbersArePinned) {
  EXPECT_EQ(RW_API_VERSION_MAJOR, 1);
  // 1.1: rw_set_pressure_limit added; 1.2: rw_patch's wheel-frame location appended; 1.3:
  // RW_MODEL_HERTZ with rolling contact (the fast tread path) and rw_get_patch_model; 1.4: the
  // fast tread path on a wheelset handle too; 1.5: rw_model's normal solver stopping rule
  // appended (the strict setting), a failed internal check returns RW_ERROR_INTERNAL, and
  // rw_set_warm_start.
  EXPECT_EQ(RW_API_VERSION_MINOR, 5);
  EXPECT_EQ(RW_API_VERSION_PATCH, 0);
  EXPECT_EQ(RW_API_VERSION, 10500);
  EXPECT_EQ(rw_api_version(), RW_API_VERSION);  // the library is the header's
}

// LP64 (x86-64, aarch64 Linux): size_t and double 8 bytes, int and uint32_t 4.
TEST(ApiAbi, StructSizesArePinnedAndEqualInCAndCpp) {
  static_assert(sizeof(void*) == 8, "the pinned sizes are those of an LP64 platform");
  const size_t cpp[] = {sizeof(rw_material), sizeof(rw_model), sizeof(rw_influence_constants),
                        sizeof(rw_geometry), sizeof(rw_state), sizeof(rw_summary),
                        sizeof(rw_patch),    sizeof(rw_wear)};
  const size_t pinned[] = {40, 72, 88, 56, 136, 104, 208, 32};
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(rw_test_c_sizeof(i), cpp[i]) << "struct " << i;
    EXPECT_EQ(cpp[i], pinned[i]) << "struct " << i;
  }
  // The size is the first member of every versioned struct.
  EXPECT_EQ(offsetof(rw_material, struct_size), 0u);
  EXPECT_EQ(offsetof(rw_model, struct_size), 0u);
  EXPECT_EQ(offsetof(rw_influence_constants, struct_size), 0u);
  EXPECT_EQ(offsetof(rw_geometry, struct_size), 0u);
  EXPECT_EQ(offsetof(rw_state, struct_size), 0u);
  EXPECT_EQ(offsetof(rw_summary, struct_size), 0u);
  EXPECT_EQ(offsetof(rw_patch, struct_size), 0u);
  EXPECT_EQ(offsetof(rw_wear, struct_size), 0u);
  // rw_patch of 1.0 and 1.1, still accepted: everything before the wheel-frame location.
  EXPECT_EQ(RW_PATCH_SIZE_1_1, 184u);
  EXPECT_EQ(rw_test_c_sizeof(8), RW_PATCH_SIZE_1_1);
  // rw_model of 1.0 to 1.4, still accepted: everything before the normal solver's stopping rule.
  EXPECT_EQ(RW_MODEL_SIZE_1_4, 48u);
  EXPECT_EQ(rw_test_c_sizeof(9), RW_MODEL_SIZE_1_4);
}

TEST(ApiAbi, EnumValuesArePinned) {
  EXPECT_EQ(RW_OK, 0);
  EXPECT_EQ(RW_ERROR_WRONG_KIND, 13);
  EXPECT_EQ(RW_PROBLEM_WHEELSET, 1);
  EXPECT_EQ(RW_MODEL_AUTO, 4);
  EXPECT_EQ(RW_ACCURACY_FINE, 3);
  EXPECT_EQ(RW_TANGENTIAL_AUTO, 2);
  EXPECT_EQ(RW_EFFECT_COUPLING, 0x4u);
  EXPECT_EQ(RW_STATE_CREEPAGE, 0x1u);
  EXPECT_EQ(RW_WEAR_USFD, 3);
  EXPECT_EQ(RW_PRESSURE_LIMIT_NONE, 0);
  EXPECT_EQ(RW_PRESSURE_LIMIT_HARDNESS, 1);
  EXPECT_EQ(RW_PRESSURE_LIMIT_VALUE, 2);
  EXPECT_EQ(RW_ERROR_INTERNAL, 11);
  EXPECT_EQ(RW_NORMAL_PRESSURE_UPDATE, 0);
  EXPECT_EQ(RW_NORMAL_GAP_RESIDUAL, 1);
}

// A caller built against 1.4 passes rw_model's 1.4 size (RW_MODEL_SIZE_1_4, without the normal
// solver's stopping rule): rw_init_model fills only those bytes, rw_set_model takes it with the
// stopping rule's defaults, and the solve equals a 1.5 caller's default model bit for bit.
TEST(ApiAbi, AModelOfVersion14StillWorks) {
  constexpr unsigned char kCanary = 0xA5;
  unsigned char bytes[sizeof(rw_model)];
  std::memset(bytes, kCanary, sizeof bytes);
  rw_model old{};
  std::memcpy(&old, bytes, sizeof old);
  old.struct_size = RW_MODEL_SIZE_1_4;
  ASSERT_EQ(rw_init_model(&old), RW_OK);
  EXPECT_EQ(old.struct_size, RW_MODEL_SIZE_1_4);
  EXPECT_EQ(old.kind, RW_MODEL_CONFORMAL);
  // Nothing written past the 1.4 struct.
  const unsigned char* tail = reinterpret_cast<const unsigned char*>(&old) + RW_MODEL_SIZE_1_4;
  for (size_t i = 0; i < sizeof(rw_model) - RW_MODEL_SIZE_1_4; ++i) {
    EXPECT_EQ(tail[i], kCanary) << "byte " << RW_MODEL_SIZE_1_4 + i;
  }
  old.kind = RW_MODEL_HALFSPACE;
  old.accuracy = RW_ACCURACY_DRAFT;
  rw_model now{};
  now.struct_size = sizeof now;
  ASSERT_EQ(rw_init_model(&now), RW_OK);
  EXPECT_EQ(now.normal_criterion, RW_NORMAL_PRESSURE_UPDATE);
  EXPECT_EQ(now.normal_tolerance, 0.0);
  EXPECT_EQ(now.tangential_tolerance, 0.0);
  now.kind = RW_MODEL_HALFSPACE;
  now.accuracy = RW_ACCURACY_DRAFT;
  double p_max[2] = {-1.0, -1.0};
  for (int i = 0; i < 2; ++i) {
    rw_problem* p = nullptr;
    ASSERT_EQ(rw_create(RW_PROBLEM_WHEEL, &p), RW_OK);
    ASSERT_EQ(rw_set_profile_file(p, RW_BODY_WHEEL, "circle:300"), RW_OK);
    ASSERT_EQ(rw_set_profile_file(p, RW_BODY_RAIL, "circle:300"), RW_OK);
    ASSERT_EQ(rw_set_model(p, i == 0 ? &old : &now), RW_OK) << rw_last_error(p);
    rw_state state{};
    state.struct_size = sizeof state;
    rw_init_state(&state);
    state.vertical_force_N = 50e3;
    ASSERT_EQ(rw_set_state(p, &state), RW_OK);
    ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
    rw_patch patch{};
    patch.struct_size = sizeof patch;
    ASSERT_EQ(rw_get_patch(p, 0, &patch), RW_OK);
    p_max[i] = patch.p_max_Pa;
    rw_destroy(p);
  }
  EXPECT_GT(p_max[0], 0.0);
  EXPECT_EQ(p_max[0], p_max[1]);
}

TEST(ApiAbi, ACProgramSolvesAsCppDoes) {
  // Hertz, a wheel of 300 mm lateral radius on a rail crown of 300 mm at 50 kN, from C: the same
  // peak pressure as the same calls from C++, bit for bit.
  const double from_c = rw_test_c_solve();
  ASSERT_GT(from_c, 0.0) << "status " << -from_c;
  rw_problem* p = nullptr;
  ASSERT_EQ(rw_create(RW_PROBLEM_WHEEL, &p), RW_OK);
  rw_model model{};
  model.struct_size = sizeof model;
  rw_init_model(&model);
  model.kind = RW_MODEL_HERTZ;
  rw_state state{};
  state.struct_size = sizeof state;
  rw_init_state(&state);
  state.vertical_force_N = 50e3;
  ASSERT_EQ(rw_set_profile_file(p, RW_BODY_WHEEL, "circle:300"), RW_OK);
  ASSERT_EQ(rw_set_profile_file(p, RW_BODY_RAIL, "circle:300"), RW_OK);
  ASSERT_EQ(rw_set_model(p, &model), RW_OK);
  ASSERT_EQ(rw_set_state(p, &state), RW_OK);
  ASSERT_EQ(rw_calculate(p), RW_OK) << rw_last_error(p);
  rw_patch patch{};
  patch.struct_size = sizeof patch;
  ASSERT_EQ(rw_get_patch(p, 0, &patch), RW_OK);
  EXPECT_EQ(patch.p_max_Pa, from_c);
  rw_destroy(p);
}

}  // namespace
