#pragma once
// The thesis' spatial index for finding cloth vertices inside the body before
// a solve (ch. 4, Alg. 1): each bone of the skeleton is cut into intervals of
// one length; each body triangle is filed under the bone nearest its centre
// and the interval its centre projects to. A point is then tested against the
// triangles filed under the bone nearest it, in its interval and the two
// beside it (a triangle whose centre projects just across an interval's end
// may still cover the point's direction), instead of against the whole body.
//
// The test casts a ray from the point's projection on its bone (inside the
// body) through the point: the point is inside when the ray crosses the
// filed triangles an even number of times before reaching it. That parity
// holds when the filed triangles are all the surface the ray meets, which the
// index cannot know (a point inside the trunk near the armpit may be nearer
// the arm's bone, whose triangles do not hold the trunk's side); so an
// `outside` verdict is the thesis' approximation, measured against the exact
// surface in docs/sensitivity.md, and the push-out (ClothProblem::
// push_out_of_bodies) still asks the exact body for every point the index
// does not place clearly outside. A ray that meets no filed triangle, passes
// within 1e-7 (barycentric) of a triangle's edge, or starts from a piece of
// bone that is not inside the mesh gives `unknown`.

#include "contact/body_obj.hpp"
#include "contact/mannequin.hpp"
#include "contact/shape.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace sartor::contact {

class BoneIntervals {
public:
  // `mesh`: a closed, outward-oriented body mesh (check_body_mesh); `bones`:
  // segments inside it; `interval`: the intervals' length, m (> 0). Throws
  // InputError for no bones or a bad interval.
  BoneIntervals(const BodyMesh& mesh, const std::vector<Bone>& bones, double interval);

  enum class Side { inside, outside, unknown };
  struct Detection {
    Side side = Side::unknown;
    // From the point to the surface along the ray from the bone, m: > 0
    // inside, < 0 outside; 0 when unknown.
    double depth = 0.0;
    std::size_t bone = 0; // the bone nearest the point
  };
  // Alg. 1, lines 12 to 15, for a point in the mesh's frame.
  Detection detect(const Eigen::Vector3d& x) const;

  // Whether the exact surface must be asked about x: anything but `outside`
  // by more than `margin` (m).
  bool may_be_inside(const Eigen::Vector3d& x, double margin) const {
    const Detection d = detect(x);
    return d.side != Side::outside || d.depth > -margin;
  }

  std::size_t bones() const { return bones_.size(); }
  std::size_t intervals() const;
  std::size_t triangles() const { return triangles_.size(); }
  // The most triangles filed under one interval.
  std::size_t largest_interval() const;
  // The pieces of bone (intervals) whose ends are not all inside the mesh:
  // points nearest them get `unknown`.
  std::size_t intervals_outside() const;

private:
  struct FiledBone {
    Eigen::Vector3d start, axis; // axis: end - start
    double length = 0.0;
    std::vector<std::vector<int>> intervals; // triangle indices per interval
    std::vector<bool> usable;                // the interval lies inside the mesh
  };
  struct Triangle {
    Eigen::Vector3d p0, e1, e2; // corner and the two edges from it
  };
  // The nearest bone and the parameter in [0, 1] of x's projection on it.
  std::pair<std::size_t, double> nearest_bone(const Eigen::Vector3d& x) const;
  int interval_of(const FiledBone& bone, double parameter) const;
  bool inside_by_all_triangles(const Eigen::Vector3d& x) const;

  double interval_;
  std::vector<Triangle> triangles_;
  std::vector<FiledBone> bones_;
};

// The largest distance between a body mesh and the exact surface it stands
// for (the mannequin's implicit surface is polygonised), sampled at the
// mesh's vertices, edge midpoints and triangle centres, m. 0 for a mesh
// body's own mesh.
double mesh_deviation(const BodyMesh& mesh, const Shape& shape);

} // namespace sartor::contact
