#pragma once
// The design space of `sartor edit`: the corners of every panel's outline
// (the starts of its lines), then the two inner control points of every
// Bezier outline line, two coordinates each. A design p moves them; each
// outline line follows by blending its two corners' moves along its arc
// length (a line whose both corners move by d translates by d), plus its
// control points' moves by their Bernstein weights 3t(1-t)^2 and 3t^2(1-t)
// (a curve edit), and the panel's interior follows its outline by positive
// mean value coordinates (or mean value coordinates;
// garment/pattern_edit.hpp). The change of the mesh's rest coordinates is
// linear in p.

#include "app/edit_case.hpp"
#include "garment/pattern.hpp"
#include "garment/pattern_edit.hpp"
#include "mesh/triangle_mesh.hpp"
#include "solvers/sensitivity.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <map>
#include <string>
#include <vector>

namespace sartor {

class EditDesign {
public:
  // `mesh`: the cloth, its material coordinates those of each panel's grain
  // (garment's panel mesher); `panel_of_triangle` indexes pattern.panels.
  EditDesign(
      const garment::Pattern& pattern, const TriangleMesh& mesh,
      const std::vector<int>& panel_of_triangle,
      garment::InteriorCoordinates interior = garment::InteriorCoordinates::positive_mean_value);

  Eigen::Index size() const { return Eigen::Index(2 * slots_); }
  // The parameters of a step's (or a drag parameter's) moves (added to
  // those of the steps before).
  Eigen::VectorXd parameters(const std::vector<CornerMove>& moves) const;
  // The change of the rest coordinates of `mesh` for parameters p: the
  // cloth mesh the design was made for, or one with its vertices and other
  // triangles (Delaunay smoothing flips edges, the vertices stay).
  RestChange rest_change(const Eigen::VectorXd& p, const TriangleMesh& mesh) const;
  // Each panel's outline polygon (pattern coordinates) moved by p.
  std::vector<std::vector<Eigen::Vector2d>> outlines(const Eigen::VectorXd& p) const;
  // The largest move of a corner or control point in p, m.
  double largest_move(const Eigen::VectorXd& p) const;

private:
  struct OutlinePoint {
    Eigen::Vector2d at;
    int first_corner = 0; // global corner index of the line's start
    int second_corner = 0;
    double s = 0.0; // arc-length fraction along the line
    // A Bezier line's: the slot of its first inner control point (the
    // second is the next), and the point's Bezier parameter.
    int first_control = -1;
    double t = 0.0;
  };
  // The slots a move moves (corners, or a control point).
  std::vector<int> moved_slots(const CornerMove& move) const;
  struct VertexWeights {
    std::vector<std::pair<int, double>> slots; // design slot (corner or control point), weight
    int panel = -1;
  };
  const garment::Pattern& pattern_;
  const TriangleMesh& mesh_;
  int corners_ = 0;
  int slots_ = 0; // the corners, then two per Bezier outline line
  std::vector<int> first_corner_of_panel_;
  std::map<std::pair<std::size_t, std::size_t>, int> first_control_; // (panel, line)
  std::vector<std::vector<OutlinePoint>> polygons_;                  // per panel
  std::vector<VertexWeights> vertices_;
};

// Rank 0: an SVG of the panels' outlines before (grey) and after (red) an
// edit, side by side as the pattern sheet lays them out.
void write_edit_svg(const std::string& path, const garment::Pattern& pattern,
                    const std::vector<std::vector<Eigen::Vector2d>>& before,
                    const std::vector<std::vector<Eigen::Vector2d>>& after,
                    const std::string& title);

// The same outlines as data (edit_NN/outlines.json, which
// postproc/plot_edit.py draws): per panel its id and the outline before
// and after, each a list of [x, y] points (m) laid out as the pattern sheet.
nlohmann::json edit_outlines_json(const garment::Pattern& pattern,
                                  const std::vector<std::vector<Eigen::Vector2d>>& before,
                                  const std::vector<std::vector<Eigen::Vector2d>>& after,
                                  const std::string& title);

} // namespace sartor
