// Enum names (from the tables in contact_types.h) and small helpers of contact_types.h.
#include "core/contact/contact_types.h"

#include <cmath>
#include <numbers>

#include "core/numerics/check.h"

namespace railwear {

double Material::Compliance() const {
  return (1.0 - poisson_ratio * poisson_ratio) / (std::numbers::pi * youngs_modulus_Pa);
}

double ContactModulus(const Material& a, const Material& b) {
  const double inv = (1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus_Pa +
                     (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus_Pa;
  return 1.0 / inv;
}

InfluenceConstantSet InfluenceConstants::ForBody(int sign) const {
  if (!separate) return {c_f, c_z, c_s};
  RAILWEAR_CHECK(sign == -1 || sign == +1);
  return sign < 0 ? separate->convex : separate->concave;
}

int BodyCurvatureSign(double curvature_per_m) { return curvature_per_m > 0 ? -1 : +1; }

std::string_view ToString(KernelModel v) { return EnumToString(kKernelModelNames, v); }
std::string_view ToString(ModelKind v) { return EnumToString(kModelKindNames, v); }
std::string_view ToString(AccuracyPreset v) { return EnumToString(kAccuracyPresetNames, v); }
std::string_view ToString(PressureLimitKind v) { return EnumToString(kPressureLimitKindNames, v); }

std::optional<double> PressureLimitOf(const PressureLimit& limit, const Material& wheel,
                                      const Material& rail) {
  switch (limit.kind) {
    case PressureLimitKind::kNone:
      return std::nullopt;
    case PressureLimitKind::kValue:
      return limit.value_Pa;
    case PressureLimitKind::kHardness: {
      // The softer body yields first; a body without a hardness does not bound the pressure.
      double h = std::numeric_limits<double>::quiet_NaN();
      for (const double v : {wheel.hardness_Pa, rail.hardness_Pa}) {
        if (v > 0.0 && !(h <= v)) h = v;
      }
      return h;
    }
  }
  return std::nullopt;
}

std::optional<KernelModel> KernelModelFromString(std::string_view s) {
  return EnumFromString(kKernelModelNames, s);
}
std::optional<ModelKind> ModelKindFromString(std::string_view s) {
  return EnumFromString(kModelKindNames, s);
}
std::optional<AccuracyPreset> AccuracyPresetFromString(std::string_view s) {
  return EnumFromString(kAccuracyPresetNames, s);
}

ModelOptions MakeModelOptions(ModelKind kind) {
  ModelOptions o;
  o.kind = kind;
  switch (kind) {
    case ModelKind::kHertz:
    case ModelKind::kHalfspace:
      o.geometry = GeometryModel::kPlanar;
      o.kernel = KernelModel::kBoussinesq;
      break;
    case ModelKind::kConformal:
    case ModelKind::kCustom:
      o.geometry = GeometryModel::kConformal;
      o.kernel = KernelModel::kGolubenko;
      break;
    case ModelKind::kAuto:  // the conformal patches' choice; FEM evidence, DESIGN.md §1
      o.geometry = GeometryModel::kConformal;
      o.kernel = KernelModel::kBoussinesq;
      break;
  }
  return o;
}

}  // namespace railwear
