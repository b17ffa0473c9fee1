#include "contact/mesh_shape.hpp"

#include "common/error.hpp"
#include "contact/body_obj.hpp"
#include "contact/mannequin.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <iterator>
#include <sstream>
#include <unordered_map>

namespace sartor::contact {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalPoint = Kernel::Point_3;
using CgalTriangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<CgalTriangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

enum class Feature { face, edge, vertex };

// The point of triangle (a, b, c) nearest to p and the feature it lies on:
// `index` is the corner (vertex) or the edge's first corner (edge k runs
// from corner k to corner k + 1). Regions are told apart by the signs of
// the projections of p onto the edges, as in Voronoi-region tests.
struct Nearest {
  Eigen::Vector3d point;
  Feature feature;
  int index;
};

Nearest nearest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  const Eigen::Vector3d ap = p - a;
  const double ab_ap = ab.dot(ap);
  const double ac_ap = ac.dot(ap);
  if (ab_ap <= 0.0 && ac_ap <= 0.0) return {a, Feature::vertex, 0};
  const Eigen::Vector3d bp = p - b;
  const double ab_bp = ab.dot(bp);
  const double ac_bp = ac.dot(bp);
  if (ab_bp >= 0.0 && ac_bp <= ab_bp) return {b, Feature::vertex, 1};
  const double area_c = ab_ap * ac_bp - ab_bp * ac_ap; // barycentric weight of c, scaled
  if (area_c <= 0.0 && ab_ap >= 0.0 && ab_bp <= 0.0)
    return {a + (ab_ap / (ab_ap - ab_bp)) * ab, Feature::edge, 0};
  const Eigen::Vector3d cp = p - c;
  const double ab_cp = ab.dot(cp);
  const double ac_cp = ac.dot(cp);
  if (ac_cp >= 0.0 && ab_cp <= ac_cp) return {c, Feature::vertex, 2};
  const double area_b = ab_cp * ac_ap - ab_ap * ac_cp;
  if (area_b <= 0.0 && ac_ap >= 0.0 && ac_cp <= 0.0)
    return {a + (ac_ap / (ac_ap - ac_cp)) * ac, Feature::edge, 2};
  const double area_a = ab_bp * ac_cp - ab_cp * ac_bp;
  if (area_a <= 0.0 && ac_bp - ab_bp >= 0.0 && ab_cp - ac_cp >= 0.0) {
    const double t = (ac_bp - ab_bp) / ((ac_bp - ab_bp) + (ab_cp - ac_cp));
    return {b + t * (c - b), Feature::edge, 1};
  }
  const double total = area_a + area_b + area_c;
  return {a + (area_b / total) * ab + (area_c / total) * ac, Feature::face, 0};
}

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

class MeshShape final : public Shape {
public:
  MeshShape(BodyMesh mesh, std::string name, double smoothing)
      : mesh_(std::move(mesh)), name_(std::move(name)), smoothing_(smoothing) {
    const std::size_t face_count = mesh_.faces.size();
    triangles_.reserve(face_count);
    face_normals_.resize(face_count);
    face_edges_.resize(face_count);
    vertex_normals_.assign(mesh_.vertices.size(), Eigen::Vector3d::Zero());
    std::unordered_map<std::uint64_t, std::size_t> edge_index;
    edge_index.reserve(3 * face_count / 2);
    Eigen::Vector3d lower = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d upper = -lower;
    for (std::size_t f = 0; f < face_count; ++f) {
      const auto& face = mesh_.faces[f];
      std::array<Eigen::Vector3d, 3> p;
      for (int k = 0; k < 3; ++k) {
        p[k] = vertex(face[k]);
        lower = lower.cwiseMin(p[k]);
        upper = upper.cwiseMax(p[k]);
      }
      triangles_.emplace_back(CgalPoint(p[0].x(), p[0].y(), p[0].z()),
                              CgalPoint(p[1].x(), p[1].y(), p[1].z()),
                              CgalPoint(p[2].x(), p[2].y(), p[2].z()));
      face_normals_[f] = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
      for (int k = 0; k < 3; ++k) {
        // Angle-weighted vertex pseudo-normal; an edge's is the sum of its faces' normals.
        const Eigen::Vector3d along = p[(k + 1) % 3] - p[k];
        const Eigen::Vector3d back = p[(k + 2) % 3] - p[k];
        const double angle = std::atan2(along.cross(back).norm(), along.dot(back));
        vertex_normals_[static_cast<std::size_t>(face[k])] += angle * face_normals_[f];
        const auto [it, inserted] =
            edge_index.try_emplace(edge_key(face[k], face[(k + 1) % 3]), edge_normals_.size());
        if (inserted) edge_normals_.push_back(Eigen::Vector3d::Zero());
        edge_normals_[it->second] += face_normals_[f];
        face_edges_[f][k] = it->second;
      }
    }
    for (auto& n : edge_normals_)
      n.normalize();
    for (auto& n : vertex_normals_)
      if (n.squaredNorm() > 0.0) n.normalize();
    tiny_distance_ = 1e-12 * (upper - lower).norm();
    tree_.insert(triangles_.begin(), triangles_.end());
    tree_.build();
    tree_.accelerate_distance_queries();
    // The first query builds the search structure; do it now, so that later
    // queries only read (and may run concurrently).
    (void)tree_.closest_point(CgalPoint(lower.x(), lower.y(), lower.z()));
  }

  SurfaceQuery query(const Eigen::Vector3d& p) const override {
    const auto hit = tree_.closest_point_and_primitive(CgalPoint(p.x(), p.y(), p.z()));
    const auto f = static_cast<std::size_t>(hit.second - triangles_.begin());
    const auto& face = mesh_.faces[f];
    const Nearest nearest =
        nearest_on_triangle(p, vertex(face[0]), vertex(face[1]), vertex(face[2]));
    const Eigen::Vector3d offset = p - nearest.point;
    const double gap = offset.norm();
    const Eigen::Vector3d& pseudo_normal =
        nearest.feature == Feature::face ? face_normals_[f]
        : nearest.feature == Feature::edge
            ? edge_normals_[face_edges_[f][nearest.index]]
            : vertex_normals_[static_cast<std::size_t>(face[nearest.index])];
    const double sign = offset.dot(pseudo_normal) >= 0.0 ? 1.0 : -1.0;
    SurfaceQuery result;
    result.closest = nearest.point;
    result.distance = sign * gap;
    if (smoothing_ > 0.0 && gap > tiny_distance_) {
      smoothed(p, gap, sign, &result);
      return result;
    }
    if (nearest.feature == Feature::face || gap <= tiny_distance_) {
      result.normal = pseudo_normal;
      return result;
    }
    result.normal = (sign / gap) * offset;
    const Eigen::Matrix3d across =
        Eigen::Matrix3d::Identity() - result.normal * result.normal.transpose();
    if (nearest.feature == Feature::edge) {
      const Eigen::Vector3d along =
          (vertex(face[(nearest.index + 1) % 3]) - vertex(face[nearest.index])).normalized();
      result.hessian = (across - along * along.transpose()) / result.distance;
    } else {
      result.hessian = across / result.distance;
    }
    return result;
  }

  std::string describe() const override {
    std::string text = "mesh " + name_ + " (" + std::to_string(mesh_.faces.size()) + " triangles";
    if (smoothing_ > 0.0) {
      std::ostringstream eps;
      eps << smoothing_;
      text += ", distance smoothed over " + eps.str() + " m";
    }
    return text + ")";
  }

private:
  const Eigen::Vector3d& vertex(int index) const {
    return mesh_.vertices[static_cast<std::size_t>(index)];
  }

  // The soft minimum over the triangles within the ball of radius
  // gap + 12 eps (farther ones weigh less than exp(-12)); see the header.
  void smoothed(const Eigen::Vector3d& p, double gap, double sign, SurfaceQuery* result) const {
    const double reach = gap + 12.0 * smoothing_;
    const Kernel::Sphere_3 ball(CgalPoint(p.x(), p.y(), p.z()), reach * reach);
    std::vector<Tree::Primitive_id> near;
    tree_.all_intersected_primitives(ball, std::back_inserter(near));
    double total = 0.0;
    Eigen::Vector3d mean_direction = Eigen::Vector3d::Zero();
    Eigen::Matrix3d curvature = Eigen::Matrix3d::Zero(), spread = Eigen::Matrix3d::Zero();
    for (const auto& id : near) {
      const auto& face = mesh_.faces[static_cast<std::size_t>(id - triangles_.begin())];
      const Nearest n = nearest_on_triangle(p, vertex(face[0]), vertex(face[1]), vertex(face[2]));
      const Eigen::Vector3d away = p - n.point;
      const double g = away.norm();
      const double w = std::exp(-(g - gap) / smoothing_);
      const Eigen::Vector3d u = away / g;
      total += w;
      mean_direction += w * u;
      spread += w * u * u.transpose();
      if (n.feature == Feature::face) continue; // a plane: no curvature
      Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - u * u.transpose();
      if (n.feature == Feature::edge) {
        const Eigen::Vector3d along =
            (vertex(face[(n.index + 1) % 3]) - vertex(face[n.index])).normalized();
        across -= along * along.transpose();
      }
      curvature += (w / g) * across;
    }
    const Eigen::Vector3d gradient = mean_direction / total;
    const Eigen::Matrix3d hessian =
        curvature / total - (spread / total - gradient * gradient.transpose()) / smoothing_;
    result->distance = sign * (gap - smoothing_ * std::log(total));
    result->normal = sign * gradient;
    result->hessian = sign * hessian;
    result->closest = p - result->distance * result->normal;
  }

  BodyMesh mesh_;
  std::string name_;
  std::vector<CgalTriangle> triangles_; // the tree refers to these
  std::vector<Eigen::Vector3d> face_normals_;
  std::vector<std::array<std::size_t, 3>> face_edges_; // edge k of face f: index into edge_normals_
  std::vector<Eigen::Vector3d> edge_normals_;
  std::vector<Eigen::Vector3d> vertex_normals_;
  double tiny_distance_ = 0.0;
  double smoothing_ = 0.0; // m; 0: the exact distance
  Tree tree_;
};

} // namespace

std::unique_ptr<Shape> make_mesh_shape(const std::vector<Eigen::Vector3d>& vertices,
                                       const std::vector<std::array<int, 3>>& faces,
                                       const std::string& name, double smoothing) {
  BodyMesh mesh{vertices, faces};
  check_body_mesh(mesh, name);
  return std::make_unique<MeshShape>(std::move(mesh), name, smoothing);
}

std::unique_ptr<Shape> load_mesh_shape(const std::string& path, double smoothing) {
  return std::make_unique<MeshShape>(read_body_obj(path), path, smoothing);
}

std::unique_ptr<Shape> make_mannequin_shape() {
  const Mannequin& mannequin = default_mannequin();
  return std::make_unique<MeshShape>(mannequin.mesh, "mannequin", 0.0);
}

} // namespace sartor::contact
