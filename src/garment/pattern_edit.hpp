#pragma once
// Pattern edits as parameters of the design sensitivity (docs/sensitivity.md):
// a panel's outline control points move, and the panel's interior follows
// by mean value coordinates (Floater 2003) of the outline polygon, so the
// change of every material point is linear in the edit:
//     du(p) = sum_i lambda_i(p) dP_i,
// lambda_i(p) the mean value coordinates of p in the polygon of the control
// points P_i. They reproduce affine maps exactly (an edit that moves the
// outline by an affine map moves the panel by it), interpolate linearly along
// the outline's edges, and are smooth inside; in a non-convex polygon some
// may be negative (the positive coordinates of Lipman et al. are not
// implemented).

#include <Eigen/Core>

#include <vector>

namespace sartor::garment {

// The mean value coordinates of `point` with respect to the closed polygon
// `outline` (either orientation, at least three points, no two consecutive
// points equal): one weight per outline point, summing to 1. A point on an
// edge or at a corner gets the linear interpolation of that edge. Throws
// InputError for fewer than three points or a degenerate edge.
std::vector<double> mean_value_coordinates(const std::vector<Eigen::Vector2d>& outline,
                                           const Eigen::Vector2d& point);

// The change of each of `points` when the outline's points move by `delta`
// (one per outline point).
std::vector<Eigen::Vector2d> outline_edit(const std::vector<Eigen::Vector2d>& outline,
                                          const std::vector<Eigen::Vector2d>& delta,
                                          const std::vector<Eigen::Vector2d>& points);

// A symmetric edit: the changes `delta` of the outline's points plus their
// mirror images about the line through `origin` along `axis`, applied to the
// points `mirror[i]` (the index of point i's mirror image in the outline, or
// -1 for none): the edit of the left side carried over to the right.
std::vector<Eigen::Vector2d> symmetric_edit(const std::vector<Eigen::Vector2d>& delta,
                                            const std::vector<int>& mirror,
                                            const Eigen::Vector2d& axis);

} // namespace sartor::garment
