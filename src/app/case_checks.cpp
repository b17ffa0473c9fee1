#include "app/case_checks.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sartor {

void check_mesh_size(double triangles, int refinements, const std::string& what) {
  const double total = triangles * std::pow(4.0, refinements);
  if (total <= double(max_case_triangles)) return;
  std::ostringstream message;
  message << what << ": the mesh would have " << total << " triangles, more than the "
          << max_case_triangles << " a case may have; give fewer divisions or refinements";
  throw InputError(message.str());
}

void check_time_divisions(double span, const std::string& span_option, double step,
                          const std::string& step_option) {
  if (step <= 0.0 || span / step <= max_time_divisions) return;
  std::ostringstream message;
  message << "option --" << step_option << ": " << step << " s divides --" << span_option << " ("
          << span << " s) into " << span / step << " parts, more than the " << max_time_divisions
          << " a run may have";
  throw InputError(message.str());
}

void check_simulated_time(double time, const std::string& option) {
  if (time <= max_simulated_time) return;
  std::ostringstream message;
  message << "option --" << option << ": " << time << " s is longer than the " << max_simulated_time
          << " s (300 years) a run may simulate";
  throw InputError(message.str());
}

void check_panel_mesh_size(const garment::Pattern& pattern, double edge_length) {
  double triangles = 0.0;
  for (const garment::Panel& panel : pattern.panels) {
    Eigen::AlignedBox2d box;
    double perimeter = 0.0; // a curve is no longer than its control polygon
    for (const garment::OutlineLine& line : panel.outline) {
      const auto& points = line.curve.points;
      for (std::size_t i = 0; i < points.size(); ++i) {
        box.extend(points[i]);
        if (i > 0) perimeter += (points[i] - points[i - 1]).norm();
      }
    }
    // Equilateral triangles of side edge_length fill the box, and the
    // boundary adds a row of them.
    const double area = box.isEmpty() ? 0.0 : box.sizes().prod();
    triangles +=
        area / (0.25 * std::sqrt(3.0) * edge_length * edge_length) + 2.0 * perimeter / edge_length;
  }
  if (triangles <= double(max_case_triangles)) return;
  std::ostringstream message;
  message << "option --edge-length: " << edge_length << " m would mesh the panels of "
          << pattern.source << " into up to " << triangles << " triangles, more than the "
          << max_case_triangles << " a case may have; give a longer edge length";
  throw InputError(message.str());
}

void reject_unmet_residual(double force_scale, StaticReport* report) {
  const double met = std::max(1e-6 * report->initial_residual_norm, 1e-9 * force_scale);
  if (!report->converged || report->final_residual_norm <= met) return;
  report->converged = false;
  report->reason += " with the residual above its tolerance";
}

namespace {

bool is_flat(const TriangleMesh& mesh) {
  if (mesh.triangle_count() == 0) return false;
  Eigen::Vector3d lowest = mesh.positions.front(), highest = lowest;
  for (const auto& p : mesh.positions) {
    lowest = lowest.cwiseMin(p);
    highest = highest.cwiseMax(p);
  }
  const double size = (highest - lowest).norm();
  // The plane of the largest triangle; flat when every vertex is on it.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d n =
        (mesh.positions[std::size_t(t[1])] - mesh.positions[std::size_t(t[0])])
            .cross(mesh.positions[std::size_t(t[2])] - mesh.positions[std::size_t(t[0])]);
    if (n.norm() > normal.norm()) normal = n;
  }
  if (normal.norm() == 0.0) return false;
  normal.normalize();
  const Eigen::Vector3d& origin = mesh.positions.front();
  return std::all_of(mesh.positions.begin(), mesh.positions.end(), [&](const Eigen::Vector3d& p) {
    return std::abs(normal.dot(p - origin)) <= 1e-9 * size;
  });
}

} // namespace

void reject_flat_membrane_without_bending(bool quasi_static, bool pressurised,
                                          const TriangleMesh& mesh,
                                          const std::vector<ClothMaterial>& materials,
                                          const std::vector<int>& pinned) {
  const bool no_bending =
      std::all_of(materials.begin(), materials.end(),
                  [](const ClothMaterial& m) { return m.bending_stiffness == 0.0; });
  if (!quasi_static || !no_bending || pressurised) return;
  if (pinned.size() >= mesh.vertex_count() || !is_flat(mesh)) return;
  throw InputError("option --bending-stiffness: a flat membrane without bending (0) has no "
                   "stiffness out of its plane, so the static equations are singular at the "
                   "flat start; give a small bending stiffness (e.g. 1e-7 N m), an out-of-plane "
                   "imperfection (--mesh-waves) or --analysis dynamic");
}

} // namespace sartor
