#pragma once
// A rigid obstacle's geometry in its own frame: the signed distance to its
// surface with the first and second derivatives that an exact contact
// Jacobian needs. Analytic shapes (plane, sphere, capsule, box, disk) and
// triangle-mesh bodies implement it; motions over time and the contact
// penalty are built on top and know nothing of how a shape answers.

#include <Eigen/Core>

#include <string>

namespace sartor::contact {

struct SurfaceQuery {
  double distance = 0.0;                             // signed, > 0 outside, m
  Eigen::Vector3d closest = Eigen::Vector3d::Zero(); // nearest surface point, m
  // d distance / d p, outward: unit for an exact distance, shorter in the
  // fillets of a smooth implicit body (mannequin_surface.hpp).
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero(); // d^2 distance / d p^2, 1/m
};

// How much of a query a caller needs: energies and step bounds the distance
// alone, forces the normal (and closest point) too, Jacobians everything.
enum class QueryNeeds { distance, normal, curvature };

class Shape {
public:
  virtual ~Shape() = default;
  // The query at point p, in the shape's frame. Must be defined everywhere
  // (inside and outside); where the distance is not differentiable (a medial
  // axis) any one-sided value is acceptable.
  virtual SurfaceQuery query(const Eigen::Vector3d& p) const = 0;
  // The query computing only what `needs` asks for (the fields not asked for
  // keep their defaults). The fields asked for are those of query(p), bit
  // for bit. Shapes whose curvature is costly (the mannequin's implicit
  // surface, where it took most of a drape's contact time) override it.
  virtual SurfaceQuery partial_query(const Eigen::Vector3d& p, QueryNeeds /*needs*/) const {
    return query(p);
  }
  // One line for logs and summaries, e.g. "sphere r=0.3".
  virtual std::string describe() const = 0;
  // A bound on |normal| outside the body: the distance falls by at most this
  // much per metre moved. 1 for an exact distance.
  virtual double slope_bound() const { return 1.0; }
  // Friction anchors ride on the surface: a point p on it (shape frame) as a
  // point of the shape's reference frame, which moves with the surface, and
  // back; a direction at p (a tangent plane's normal) likewise. A rigid
  // shape's surface does not move in its frame (the identity); one that
  // changes with time (a mannequin bending its knees) carries each point
  // with the piece of the body it lies on.
  virtual Eigen::Vector3d to_reference(const Eigen::Vector3d& p) const { return p; }
  virtual Eigen::Vector3d from_reference(const Eigen::Vector3d& q) const { return q; }
  virtual Eigen::Vector3d direction_to_reference(const Eigen::Vector3d& /*p*/,
                                                 const Eigen::Vector3d& d) const {
    return d;
  }
  virtual Eigen::Vector3d direction_from_reference(const Eigen::Vector3d& /*q*/,
                                                   const Eigen::Vector3d& d) const {
    return d;
  }
};

} // namespace sartor::contact
