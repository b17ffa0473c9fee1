#pragma once
// The measured nonlinear anisotropic cloth of Wang, Ramamoorthi & O'Brien
// 2011 ("Data-driven elastic models for cloth"), in the JSON layout of ARCSim
// (density, a 6x4 stretching table, a 3x5 bending table), evaluated as that
// model defines (docs/fabrics.md):
//
// Stretching. Green strain G (2x2, u = warp, v = weft). The stiffness
// k = (k0, k1, k2, k3), N/m, enters the energy density (J/m^2)
//   W = 1/2 (k0 G00^2 + 2 k1 G00 G11 + k2 G11^2 + k3 G01^2).
// k depends on the largest principal stretch w (sqrt of the largest
// eigenvalue of C = I + 2G) and the angle phi of its direction to the warp,
// folded into [0, 90] degrees (0 where the principal stretches are equal,
// as ARCSim's eigensolver gives for a multiple of the identity): with s = clamp(6 (w - 1), 0, 1)
// and t = phi / 22.5 degrees between the angle rows i = floor(t), i + 1,
//   k = 2 max(0, (1 - s) row0 + s ((1 - f) row(1 + i) + f row(2 + i))),
// f = t - i: row 0 is the stiffness at zero strain, rows 1..5 at a principal
// strain of 1/6 along 0, 22.5, 45, 67.5 and 90 degrees. As ARCSim, k is
// sampled on a 30^3 grid of (G00, G11, |G01|) (G00, G11 from -0.25 in steps
// of 1/30, |G01| from 0), constant beyond the grid: this keeps k continuous
// where the principal direction is undefined (equal principal stretches).
// Between the nodes k is interpolated by Catmull-Rom cubics (ARCSim:
// trilinear), so that k, and with it the stress, is continuous across the
// cells' faces and across G01 = 0: with trilinear k the stress jumps there,
// and Newton's residual cannot fall below the jump (soft knits stalled).
// W is then an energy of G with exact first and second derivatives.
//
// Bending. Rows: fold lines at 0, 45 and 90 degrees to the warp (ARCSim's
// hinge edge direction); columns: curvature 0, 5, 10, 15, 20 1/m. The
// secant rigidity ke (N m) at curvature kappa interpolates linearly between
// columns (constant beyond 20 1/m, floored at 0); the moment per unit width
// is M = ke(kappa) kappa (N).

#include "material/tension_curve.hpp"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace sartor {

struct StretchingTable {
  std::array<std::array<double, 4>, 6> rows{}; // N/m (halved, as stored by ARCSim)
};
struct BendingTable {
  std::array<std::array<double, 5>, 3> rows{}; // N m
};

// The model's stiffness at Green strain (g00, g11, g01), directly from the
// definition (no grid).
Eigen::Vector4d table_stiffness(const StretchingTable& table, double g00, double g11, double g01);

// Energy density W (J/m^2) and its derivatives with respect to
// g = (G00, G11, G01).
struct StrainEnergy {
  double energy = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
};

class MeasuredStretching {
public:
  static constexpr int samples = 30; // grid nodes per axis
  static constexpr double spacing = 1.0 / samples;
  static constexpr double lowest = -0.25; // first node of G00 and G11
  explicit MeasuredStretching(const StretchingTable& table);

  // The interpolated stiffness and its derivatives over g (rows k0..k3).
  struct Stiffness {
    Eigen::Vector4d value = Eigen::Vector4d::Zero();
    Eigen::Matrix<double, 4, 3> gradient = Eigen::Matrix<double, 4, 3>::Zero();
    // d2k/dg_m dg_n for (m, n) = (0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2).
    std::array<Eigen::Vector4d, 6> second{Eigen::Vector4d::Zero(), Eigen::Vector4d::Zero(),
                                          Eigen::Vector4d::Zero(), Eigen::Vector4d::Zero(),
                                          Eigen::Vector4d::Zero(), Eigen::Vector4d::Zero()};
  };
  Stiffness stiffness(double g00, double g11, double g01) const;
  StrainEnergy energy(double g00, double g11, double g01) const;

  const StretchingTable& table() const { return table_; }

private:
  const Eigen::Vector4d& node(int i, int j, int k) const {
    return nodes_[std::size_t((i * samples + j) * samples + k)];
  }
  StretchingTable table_;
  std::vector<Eigen::Vector4d> nodes_;
};

// The secant rigidity ke (N m) of the bending table at curvature `curvature`
// (1/m, its magnitude is used) for a fold line at `angle` (radians) to the warp.
double table_bending_rigidity(const BendingTable& table, double curvature, double angle);

// A moment-curvature curve (moment per unit width, N; curvature 1/m),
// piecewise linear, odd: M(-k) = -M(k). Its energy density is the integral
// of M, so energy, moment and stiffness come from one source.
class MomentCurve {
public:
  static MomentCurve linear(double rigidity, const std::string& context); // N m
  // Points (curvature, moment) after the origin, strictly increasing.
  static MomentCurve piecewise(const std::vector<CurvePoint>& points, const std::string& context);
  // The points of a measured table: the moment may fall where the table's
  // rigidity softens faster than 1/curvature (11oz denim's warp between 15
  // and 20 1/m); it stays >= 0 and does not fall on the last segment.
  static MomentCurve measured(const std::vector<CurvePoint>& points, const std::string& context);
  double moment(double curvature) const;
  double stiffness(double curvature) const;      // dM/dk, N m
  double energy_density(double curvature) const; // J/m^2
  double initial_rigidity() const { return curve_.initial_modulus(); }
  const std::vector<CurvePoint>& points() const { return curve_.points(); }

private:
  explicit MomentCurve(TensionCurve curve) : curve_(std::move(curve)) {}
  TensionCurve curve_; // the branch k >= 0
};

// The moment-curvature curve of the table along one fold-line angle: through
// the table's moments ke kappa at its five curvatures and three points
// between each (ke is linear there, M quadratic), then straight with slope
// ke(20 1/m). Throws InputError naming `context` when M does not increase.
MomentCurve table_moment_curve(const BendingTable& table, double angle, const std::string& context);

// The table's tension-strain curve along the warp (`along_weft` false) or
// the weft for uniaxial strain: S = k0 G00 (k2 G11), sampled at principal
// strains j / 48, j = 1..8, then straight. `green`: as a function of Green
// strain with the second Piola-Kirchhoff tension S (the stvk model's
// measure); else of the stretch minus one with S times the stretch (the
// Baraff-Witkin model's).
TensionCurve table_tension_curve(const StretchingTable& table, bool along_weft, bool green,
                                 const std::string& context);

} // namespace sartor
