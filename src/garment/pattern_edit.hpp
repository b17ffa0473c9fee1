#pragma once
// Pattern edits as parameters of the design sensitivity (docs/sensitivity.md):
// a panel's outline control points move, and the panel's interior follows
// by coordinates lambda_i(p) of the outline polygon, so the change of every
// material point is linear in the edit:
//     du(p) = sum_i lambda_i(p) dP_i,
// P_i the control points. Two kinds of coordinates, both reproducing affine
// maps exactly (an edit that moves the outline by an affine map moves the
// panel by it) and interpolating linearly along the outline's edges:
// - mean value coordinates (Floater 2003): smooth inside, but in a non-convex
//   polygon some are negative, and the interior of a notched panel can fold;
// - positive mean value coordinates (Lipman, Kopf, Cohen-Or, Levin 2007): the
//   mean value coordinates of p with respect to the part of the outline
//   visible from p, never negative, continuous but not smooth where p's view
//   changes (on lines through a reflex corner); the same as mean value
//   coordinates where p sees the whole outline (a convex panel). The paper
//   we implement (Sensitive Couture) uses them, so they are the default.

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

// The positive mean value coordinates (Lipman et al. 2007) of `point` inside
// the closed simple polygon `outline` (either orientation): the mean value
// coordinates of the point with respect to its visibility polygon, whose
// corners on an outline edge pass their weight to that edge's two points
// linearly. One weight per outline point, all >= 0, summing to 1 and
// reproducing linear functions (sum_i lambda_i P_i = point); a point on an
// edge or at a corner gets the linear interpolation of that edge. Throws
// InputError for fewer than three points, a degenerate edge or a point
// outside the outline.
std::vector<double> positive_mean_value_coordinates(const std::vector<Eigen::Vector2d>& outline,
                                                    const Eigen::Vector2d& point);

enum class InteriorCoordinates { mean_value, positive_mean_value };

// The coordinates of the given kind of `point` in the polygon `outline`.
std::vector<double> interior_coordinates(InteriorCoordinates coordinates,
                                         const std::vector<Eigen::Vector2d>& outline,
                                         const Eigen::Vector2d& point);

// The coordinates of the point of the outline nearest `point`: the linear
// interpolation along that edge (ties: the first edge).
std::vector<double> nearest_outline_coordinates(const std::vector<Eigen::Vector2d>& outline,
                                                const Eigen::Vector2d& point);

// A mesh vertex's coordinates in its panel's outline polygon: inside (or on
// it), interior_coordinates; outside, nearest_outline_coordinates. A
// vertex on a curved line of the panel lies a little beyond the polygon
// that flattens the line, and follows the line's nearest piece.
std::vector<double> panel_coordinates(InteriorCoordinates coordinates,
                                      const std::vector<Eigen::Vector2d>& outline,
                                      const Eigen::Vector2d& point);

// The change of each of `points` when the outline's points move by `delta`
// (one per outline point), the interior following by `coordinates`.
std::vector<Eigen::Vector2d>
outline_edit(const std::vector<Eigen::Vector2d>& outline, const std::vector<Eigen::Vector2d>& delta,
             const std::vector<Eigen::Vector2d>& points,
             InteriorCoordinates coordinates = InteriorCoordinates::positive_mean_value);

// A symmetric edit: the changes `delta` of the outline's points plus their
// mirror images about the line through `origin` along `axis`, applied to the
// points `mirror[i]` (the index of point i's mirror image in the outline, or
// -1 for none): the edit of the left side carried over to the right.
std::vector<Eigen::Vector2d> symmetric_edit(const std::vector<Eigen::Vector2d>& delta,
                                            const std::vector<int>& mirror,
                                            const Eigen::Vector2d& axis);

} // namespace sartor::garment
