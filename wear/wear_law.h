// Wear laws: how much rail material a contact cell removes per metre the wheel rolls.
//
// Every law gives the local wear-depth rate per unit rolling distance, dz/dL [m per m rolled],
// from the cell's contact state. A rail point under the patch spends dx/V in a cell of length dx,
// so the depth one wheel pass removes at a lateral position is the sum of (dz/dL) dx along the
// rolling direction (DESIGN.md §1; wear/pass_depth.h does that sum).
//
// Laws and sources (reference README §6):
//  - "archard": constant coefficient, Archard (1953): volume V = k N s / H, i.e. a depth rate
//    dz/dt = k p |v_s| / H, and dz/dL = k p |v_s| / (H V). k dimensionless, H hardness [Pa].
//  - "kth": the KTH wear map of Jendel (2002, Wear 253:89-99) for dry rail steel, k by region in
//    sliding speed v_s and contact pressure p/H:
//        A  p > 0.8 H                 seizure      k = 300-400e-4
//        B  p <= 0.8 H, v_s < 0.2 m/s  mild         k = 1-10e-4
//        C  0.2 <= v_s < 0.7 m/s      severe       k = 30-40e-4
//        D  v_s >= 0.7 m/s            mild again   k = 1-10e-4
//    with the middles of the quoted ranges as defaults (350e-4, 5.5e-4, 35e-4, 5.5e-4); all four
//    are scene parameters. As published the map is discontinuous at the region boundaries.
//  - "kth-continuous": the same map with each boundary replaced by a C1 blend of log k across a
//    band (railwear's documented choice, not Jendel's): in ln v_s with half-width
//    kth_velocity_band (default 0.25, i.e. about +-28 % in v_s), and in p/H with half-width
//    kth_pressure_band (default 0.05). Outside the bands it equals the published map.
//  - "usfd": the Sheffield (USFD) wear function of R8T WHEEL steel (twin-disc tests against
//    rail steel: Lewis & Dwyer-Joyce 2004; used for wheels by Braghin et al., Wear 261 (2006)
//    1253-1264), as quoted in the reference README. railwear applies it to the rail for want of
//    a published rail-steel set (docs/wear.md "Rail grades"). Wear rate W [ug per metre rolled
//    per mm^2 of contact] against the local energy index Tg/A = |q . v_slip| / V [N/mm^2]:
//        W = 5.3 Tg/A            for Tg/A < 10.4
//        W = 55.0                for 10.4 <= Tg/A <= 77.2
//        W = 61.9 Tg/A - 4778.7  for Tg/A > 77.2
//    The published pieces do not join (at 77.2 the third gives -0.02, not 55). railwear's
//    choice makes the law continuous and monotone: W = max(min(5.3 x, 55.0), 61.9 x - 4778.7),
//    which moves the first knee to 10.38 and the second to 78.09 N/mm^2 (differences below 1 %
//    of the published knees). Depth rate = W * 1e-3 / rho [m per m rolled], W in ug/(m mm^2)
//    = 1e-3 kg/(m m^2), rho the rail density (default 7850 kg/m^3).
//
// Units: SI throughout (Pa, m/s, m); the USFD law converts internally.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "core/numerics/enum_names.h"

namespace railwear {

enum class WearLawKind { kArchard, kKth, kKthContinuous, kUsfd };
inline constexpr std::array<EnumName<WearLawKind>, 4> kWearLawKindNames = {{
    {WearLawKind::kArchard, "archard"},
    {WearLawKind::kKth, "kth"},
    {WearLawKind::kKthContinuous, "kth-continuous"},
    {WearLawKind::kUsfd, "usfd"},
}};
std::string_view ToString(WearLawKind v);
std::optional<WearLawKind> WearLawKindFromString(std::string_view s);

struct WearLaw {
  WearLawKind kind = WearLawKind::kArchard;
  double archard_k = 1e-4;  // constant Archard coefficient [-]

  // KTH map (Jendel 2002): coefficients per region [-] and the region boundaries.
  double kth_k_seizure = 350e-4;    // A: p > kth_pressure_ratio * H
  double kth_k_mild_low = 5.5e-4;   // B: v_s < kth_v1
  double kth_k_severe = 35e-4;      // C: kth_v1 <= v_s < kth_v2
  double kth_k_mild_high = 5.5e-4;  // D: v_s >= kth_v2
  double kth_v1_m_s = 0.2;
  double kth_v2_m_s = 0.7;
  double kth_pressure_ratio = 0.8;
  double kth_velocity_band = 0.25;  // kth-continuous: half-width of the blend in ln(v_s) [-]
  double kth_pressure_band = 0.05;  // kth-continuous: half-width of the blend in p/H [-]

  double density_kg_m3 = 7850.0;  // steel (rail or wheel), for the USFD law (mass -> depth)
};

// Checks the parameters (positive coefficients, v1 < v2, positive bands and density); throws
// InputError naming the parameter, its value and what was expected.
void ValidateWearLaw(const WearLaw& law);

// The contact state of one cell, as the laws need it.
struct WearCellState {
  double pressure_Pa = 0.0;              // p >= 0
  double slip_speed_m_s = 0.0;           // |v_slip| >= 0, local slip velocity magnitude
  double frictional_power_Pa_m_s = 0.0;  // |q . v_slip| >= 0, power per unit area [W/m^2]
};

// Archard-type coefficient k [-] of the KTH map (published or continuous) at a cell; the
// constant coefficient for "archard". Not defined for "usfd" (throws std::logic_error).
double WearCoefficient(const WearLaw& law, double pressure_Pa, double slip_speed_m_s,
                       double hardness_Pa);

// USFD wear rate W [ug/(m mm^2)] at the local energy index x = Tg/A [N/mm^2] >= 0, continuous
// form above.
double UsfdWearRate(double t_gamma_per_area_N_mm2);

// Depth removed per metre of rolling, dz/dL [m/m], at one cell: hardness H [Pa] > 0 (Archard and
// KTH), rolling speed V [m/s] > 0. Zero where p = 0 or there is no slip.
double WearDepthPerRolledMetre(const WearLaw& law, const WearCellState& cell, double hardness_Pa,
                               double speed_m_s);

}  // namespace railwear
