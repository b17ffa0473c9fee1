#include "material/measured_cloth.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sartor {

namespace {

constexpr double pi = 3.14159265358979323846;
// Principal strain of the table's rows 1..5 (ARCSim: "(w - 1) * 6").
constexpr double row_strain = 1.0 / 6.0;
// Curvature step of the bending table's columns, 1/m (0.05 1/cm).
constexpr double curvature_step = 5.0;
constexpr int curvature_columns = 5;

// Catmull-Rom stencil of x on the grid axis starting at `first`: the four
// nodes around it, their weights and the weights' first and second
// derivatives in x. Beyond the grid the stiffness is constant (derivatives
// zero); below node 0 a stencil takes node 0 again, or, on the |G01| axis
// (`even`), node 1 for node -1, so the stiffness is even in G01 and smooth
// across G01 = 0.
struct AxisStencil {
  std::array<int, 4> node{};
  std::array<double, 4> weight{}, slope{}, curvature{};
};

AxisStencil axis_stencil(double x, double first, bool even) {
  const double h = MeasuredStretching::spacing;
  const double scaled = (x - first) / h;
  const double last = MeasuredStretching::samples - 1;
  const bool inside = scaled < last && (even || scaled > 0.0);
  const double clamped = std::clamp(scaled, 0.0, last);
  const int cell = std::min(int(std::floor(clamped)), MeasuredStretching::samples - 2);
  const double t = clamped - cell, t2 = t * t, t3 = t2 * t;
  AxisStencil a;
  a.weight = {0.5 * (-t3 + 2.0 * t2 - t), 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
              0.5 * (-3.0 * t3 + 4.0 * t2 + t), 0.5 * (t3 - t2)};
  const double d1 = inside ? 1.0 / h : 0.0, d2 = d1 * d1;
  a.slope = {d1 * 0.5 * (-3.0 * t2 + 4.0 * t - 1.0), d1 * 0.5 * (9.0 * t2 - 10.0 * t),
             d1 * 0.5 * (-9.0 * t2 + 8.0 * t + 1.0), d1 * 0.5 * (3.0 * t2 - 2.0 * t)};
  a.curvature = {d2 * (2.0 - 3.0 * t), d2 * (9.0 * t - 5.0), d2 * (4.0 - 9.0 * t),
                 d2 * (3.0 * t - 1.0)};
  for (int n = 0; n < 4; ++n) {
    const int index = cell - 1 + n;
    a.node[std::size_t(n)] = index < 0 ? (even ? -index : 0) : std::min(index, int(last));
  }
  return a;
}

} // namespace

Eigen::Vector4d table_stiffness(const StretchingTable& table, double g00, double g11, double g01) {
  // C = I + 2G: largest eigenvalue and the angle of its direction.
  const double c00 = 1.0 + 2.0 * g00, c11 = 1.0 + 2.0 * g11, c01 = 2.0 * g01;
  const double largest = 0.5 * (c00 + c11) + std::hypot(0.5 * (c00 - c11), c01);
  const double angle = std::abs(0.5 * std::atan2(2.0 * c01, c00 - c11)); // [0, pi/2]
  const double strain_weight =
      std::clamp((std::sqrt(std::max(largest, 0.0)) - 1.0) / row_strain, 0.0, 1.0);
  const double t = std::min(angle / (pi / 8.0), 4.0);
  const int row = std::min(int(t), 3);
  const double f = t - row;
  Eigen::Vector4d k;
  for (int c = 0; c < 4; ++c) {
    const double along = (1.0 - f) * table.rows[std::size_t(1 + row)][std::size_t(c)] +
                         f * table.rows[std::size_t(2 + row)][std::size_t(c)];
    const double value =
        (1.0 - strain_weight) * table.rows[0][std::size_t(c)] + strain_weight * along;
    k[c] = 2.0 * std::max(value, 0.0);
  }
  return k;
}

MeasuredStretching::MeasuredStretching(const StretchingTable& table) : table_(table) {
  nodes_.resize(std::size_t(samples * samples * samples));
  for (int i = 0; i < samples; ++i)
    for (int j = 0; j < samples; ++j)
      for (int k = 0; k < samples; ++k)
        nodes_[std::size_t((i * samples + j) * samples + k)] =
            table_stiffness(table, lowest + i * spacing, lowest + j * spacing, k * spacing);
}

MeasuredStretching::Stiffness MeasuredStretching::stiffness(double g00, double g11,
                                                            double g01) const {
  const AxisStencil a = axis_stencil(g00, lowest, false);
  const AxisStencil b = axis_stencil(g11, lowest, false);
  AxisStencil c = axis_stencil(std::abs(g01), 0.0, true);
  if (g01 < 0.0) // k is even in G01: odd first derivatives
    for (double& slope : c.slope)
      slope = -slope;
  Stiffness s;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j)
      for (std::size_t l = 0; l < 4; ++l) {
        const Eigen::Vector4d& value = node(a.node[i], b.node[j], c.node[l]);
        const double wa = a.weight[i], wb = b.weight[j], wc = c.weight[l];
        s.value += wa * wb * wc * value;
        s.gradient.col(0) += a.slope[i] * wb * wc * value;
        s.gradient.col(1) += wa * b.slope[j] * wc * value;
        s.gradient.col(2) += wa * wb * c.slope[l] * value;
        s.second[0] += a.curvature[i] * wb * wc * value;
        s.second[1] += wa * b.curvature[j] * wc * value;
        s.second[2] += wa * wb * c.curvature[l] * value;
        s.second[3] += a.slope[i] * b.slope[j] * wc * value;
        s.second[4] += a.slope[i] * wb * c.slope[l] * value;
        s.second[5] += wa * b.slope[j] * c.slope[l] * value;
      }
  return s;
}

StrainEnergy MeasuredStretching::energy(double g00, double g11, double g01) const {
  const Stiffness k = stiffness(g00, g11, g01);
  // W = k . q / 2 with q = (G00^2, 2 G00 G11, G11^2, G01^2).
  const Eigen::Vector4d q(g00 * g00, 2.0 * g00 * g11, g11 * g11, g01 * g01);
  Eigen::Matrix<double, 4, 3> dq; // dq_i / dg_m
  dq << 2.0 * g00, 0.0, 0.0,      //
      2.0 * g11, 2.0 * g00, 0.0,  //
      0.0, 2.0 * g11, 0.0,        //
      0.0, 0.0, 2.0 * g01;
  StrainEnergy w;
  w.energy = 0.5 * k.value.dot(q);
  w.gradient = 0.5 * (k.gradient.transpose() * q + dq.transpose() * k.value);
  // d2q: q0 -> (0,0), q1 -> (0,1),(1,0), q2 -> (1,1), q3 -> (2,2), each 2.
  Eigen::Matrix3d second_q;
  second_q << 2.0 * k.value[0], 2.0 * k.value[1], 0.0, //
      2.0 * k.value[1], 2.0 * k.value[2], 0.0,         //
      0.0, 0.0, 2.0 * k.value[3];
  const Eigen::Matrix3d cross = k.gradient.transpose() * dq;
  Eigen::Matrix3d second_k; // (d2k/dg_m dg_n) . q
  second_k(0, 0) = k.second[0].dot(q);
  second_k(1, 1) = k.second[1].dot(q);
  second_k(2, 2) = k.second[2].dot(q);
  second_k(0, 1) = second_k(1, 0) = k.second[3].dot(q);
  second_k(0, 2) = second_k(2, 0) = k.second[4].dot(q);
  second_k(1, 2) = second_k(2, 1) = k.second[5].dot(q);
  w.hessian = 0.5 * (second_k + cross + cross.transpose() + second_q);
  return w;
}

double table_bending_rigidity(const BendingTable& table, double curvature, double angle) {
  // Fold-line angle folded into [0, 90] degrees; rows at 0, 45, 90.
  double folded = std::fmod(std::abs(angle), pi);
  if (folded > 0.5 * pi) folded = pi - folded;
  const double t = folded / (0.25 * pi);
  const int row = std::min(int(t), 1);
  const double f = t - row;
  const double column_position =
      std::min(std::abs(curvature) / curvature_step, double(curvature_columns - 1));
  const int column = std::min(int(column_position), curvature_columns - 2);
  const double g = column_position - column;
  const auto& r0 = table.rows[std::size_t(row)];
  const auto& r1 = table.rows[std::size_t(row + 1)];
  const auto c0 = std::size_t(column), c1 = std::size_t(column + 1);
  const double value =
      (1.0 - f) * ((1.0 - g) * r0[c0] + g * r0[c1]) + f * ((1.0 - g) * r1[c0] + g * r1[c1]);
  return std::max(value, 0.0);
}

MomentCurve MomentCurve::linear(double rigidity, const std::string& context) {
  if (!std::isfinite(rigidity) || rigidity <= 0.0) {
    std::ostringstream text;
    text << context << ": bending rigidity " << rigidity << " N m must be a finite number > 0";
    throw InputError(text.str());
  }
  return MomentCurve(TensionCurve::linear(rigidity, context));
}

namespace {
CurveRules moment_rules(bool softening) {
  return {"moment-curvature curve", "curvature", "moment", "N", softening};
}
} // namespace

MomentCurve MomentCurve::piecewise(const std::vector<CurvePoint>& points,
                                   const std::string& context) {
  return MomentCurve(TensionCurve::piecewise(points, context, moment_rules(false)));
}

MomentCurve MomentCurve::measured(const std::vector<CurvePoint>& points,
                                  const std::string& context) {
  return MomentCurve(TensionCurve::piecewise(points, context, moment_rules(true)));
}

double MomentCurve::moment(double curvature) const {
  return std::copysign(curve_.tension(std::abs(curvature)), curvature);
}

double MomentCurve::stiffness(double curvature) const {
  return curve_.stiffness(std::abs(curvature));
}

double MomentCurve::energy_density(double curvature) const {
  return curve_.energy_density(std::abs(curvature));
}

MomentCurve table_moment_curve(const BendingTable& table, double angle,
                               const std::string& context) {
  constexpr int between = 4; // points per table interval
  std::vector<CurvePoint> points;
  const double last = curvature_step * (curvature_columns - 1);
  for (int j = 1; j <= between * (curvature_columns - 1); ++j) {
    const double kappa = j * curvature_step / between;
    points.push_back({kappa, table_bending_rigidity(table, kappa, angle) * kappa});
  }
  points.push_back({2.0 * last, table_bending_rigidity(table, last, angle) * 2.0 * last});
  return MomentCurve::measured(points, context);
}

TensionCurve table_tension_curve(const StretchingTable& table, bool along_weft, bool green,
                                 const std::string& context) {
  constexpr int between = 8;
  std::vector<CurvePoint> points;
  const auto add = [&](double stretch) {
    const double e = 0.5 * (stretch * stretch - 1.0);
    const Eigen::Vector4d k =
        along_weft ? table_stiffness(table, 0.0, e, 0.0) : table_stiffness(table, e, 0.0, 0.0);
    const double s = (along_weft ? k[2] : k[0]) * e;
    points.push_back(green ? CurvePoint{e, s} : CurvePoint{stretch - 1.0, s * stretch});
  };
  for (int j = 1; j <= between; ++j)
    add(1.0 + j * row_strain / between);
  add(1.0 + 2.0 * row_strain);
  return TensionCurve::piecewise(points, context + " (stretching table)");
}

} // namespace sartor
