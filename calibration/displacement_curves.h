// Displacement curves: the reference data of influence-function calibration (the seed paper's
// experiment, issue 5), their CSV format, and what the seed's eq. 4 predicts for them.
//
// The experiment: a body whose surface is a cylinder of radius R (convex: a rail head; concave:
// a cavity or groove of radius R; flat: a half-space block) carries a unit point load at a
// surface point O. The normal displacement w of surface points is recorded against their
// distance from O along two paths:
//   arc   the cross-section through O (the curve of the cylinder): distance = arc length s
//   axis  the line through O along the cylinder's axis x: distance = x
// and three loads: normal (pressing into the body along the inward normal at O), axial
// (tangential, along +x) and circumferential (tangential, along the cross-section's tangent at O,
// toward the points of the arc path). w is the displacement of the point along the inward
// surface normal at that point (positive into the body), per newton of load.
//
// CSV format (version 1), one file per body; '#' lines before the header carry metadata:
//
//   # railwear displacement curves v1
//   # body = convex            flat | convex | concave                         (required)
//   # radius_mm = 15           surface radius, > 0 (required unless flat)
//   # E_MPa = 210000           Young's modulus, > 0                            (required)
//   # nu = 0.28                Poisson's ratio in [0, 0.5)                     (required)
//   # source = ...             any further "key = value" lines are kept as metadata: where
//   # supports = ...           the data came from, the body's size and supports, the mesh.
//   load,path,distance_mm,w_nm_per_N
//   normal,arc,0.5,2.713
//   ...
//
// Columns may come in any order, extra columns are ignored (kept out of the fit); the four named
// ones are required. w_nm_per_N is in nanometres per newton (= um/kN = 1e-9 m/N). Distances are
// positive (the load point itself is excluded); an arc distance is at most a half
// circumference (pi R). Curves that eq. 4 predicts to vanish identically (an axial load seen on
// the arc, a circumferential load seen on the axis) carry no information for a fit and are
// refused.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/contact/contact_types.h"

namespace railwear {

enum class CurveBody { kFlat, kConvex, kConcave };
enum class CurveLoad { kNormal, kAxial, kCircumferential };
enum class CurvePath { kArc, kAxis };

std::string_view ToString(CurveBody v);
std::string_view ToString(CurveLoad v);
std::string_view ToString(CurvePath v);
std::optional<CurveBody> CurveBodyFromString(std::string_view s);
std::optional<CurveLoad> CurveLoadFromString(std::string_view s);
std::optional<CurvePath> CurvePathFromString(std::string_view s);

// The seed's sign(b) of eq. 4 (c_t = 1 + c_s sign): +1 concave, -1 convex, 0 flat (c_t = 1).
int CurvatureSign(CurveBody body);

struct DisplacementPoint {
  CurveLoad load = CurveLoad::kNormal;
  CurvePath path = CurvePath::kArc;
  double distance_m = 0.0;  // > 0: arc length or axial distance from the load point [m]
  double w_m_per_N = 0.0;   // normal displacement into the body per unit load [m/N]
  int line = 0;             // line in the file it was read from (0 when not read)
};

struct DisplacementCurves {
  std::string path;  // the file it was read from (for messages); empty when built in memory
  CurveBody body = CurveBody::kFlat;
  double radius_m = 0.0;  // > 0 unless flat
  Material material;      // E and nu of the body (hardness, yield unused)
  // Every other "# key = value" metadata line, in file order (source, supports, body size,
  // mesh, ...). Keys are unique.
  std::vector<std::pair<std::string, std::string>> metadata;
  std::vector<DisplacementPoint> points;
};

// Reads a CSV of the format above. Throws InputError naming the file, the line, the column or
// metadata key, the value and what was expected: a missing or unknown header marker, missing
// metadata or columns, unknown names, numbers that are not finite, non-positive or too long
// distances, curves that eq. 4 predicts to vanish, a file without data rows.
DisplacementCurves ReadDisplacementCurves(const std::string& path);

// Writes `curves` in the format above (metadata in order, then load,path,distance_mm,w_nm_per_N
// rows with 10 significant digits). Throws InputError when the file cannot be written.
void WriteDisplacementCurves(const DisplacementCurves& curves, const std::string& path);

// The seed's eq. 4 for one point of the experiment [m/N], with constants `c` (the body's set,
// c.ForBody(CurvatureSign(body)), when they are separate per curvature sign; a flat body has no
// such set and must not be given separate constants) and the body's material (k_d, k_f and c_t
// as in core/contact/seed_kernel.h: k_d = 1 / (8 pi (1 - nu) G), k_f = (3 - 4 nu) k_d):
//   normal load:      w = (1/rho) [c_f k_f + c_z k_d dn^2/rho^2]
//   tangential load:  w = c_t k_d d_t / rho^2,  c_t = 1 + c_s CurvatureSign(body)
// with rho the chord from the load point to the field point, dn its component along the
// normal at the load point, d_t its component along the load's direction. On the arc of a
// cylinder of radius R at angle theta = s / R: rho = 2 R sin(theta/2), dn^2 = rho^2 sin^2
// (theta/2), d_t = R sin theta; on the axis (and on a flat body): rho = d_t = distance, dn = 0.
// The tangential sign is the physical one (Cerruti, Landau & Lifshitz §8): ahead of a tangential
// load the surface moves into the body, w > 0 for c_t > 0. The point must be one that
// ReadDisplacementCurves accepts (not a vanishing curve).
double SeedKernelDisplacement(const InfluenceConstants& c, CurveBody body, double radius_m,
                              const Material& material, CurveLoad load, CurvePath path,
                              double distance_m);

// The half-space (Boussinesq-Cerruti) values for a flat body [m/N]: normal (1 - nu)/(2 pi G d),
// tangential (1 - 2 nu)/(4 pi G d) (both into the body, ahead of a tangential load).
double HalfSpaceDisplacement(const Material& material, CurveLoad load, double distance_m);

// The constants with which eq. 4 reproduces the half-space values on a flat body exactly:
// c_f = 4 (1 - nu)^2 / (3 - 4 nu) (1.103 at nu = 0.28) and c_t = 2 (1 - 2 nu)(1 - nu) (0.634).
double HalfSpaceEquivalentCf(double nu);
double HalfSpaceEquivalentCt(double nu);

}  // namespace railwear
