// Progressive refinement's levels and prolongation (src/garment/mesh_levels):
// barycentric prolongation in each panel's rest coordinates carries an
// affine field exactly and a smooth one with O(h^2) error, on the CGAL
// meshes of the sample T-shirt's panels (unstructured, curved outlines);
// each level of a constructed garment sews the same lines, re-discretised;
// closing the seams joins the sewn vertices.

#include "common/error.hpp"
#include "contact/mannequin.hpp"
#include "contact/mesh_shape.hpp"
#include "garment/mesh_levels.hpp"
#include "garment/tagcon.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sartor::garment {
namespace {

const std::string samples = SARTOR_PATTERN_SAMPLES_DIR;

// Every panel of the pattern meshed flat at edge length h, one mesh,
// material_ids = panel index, positions = (u, v, 0).
TriangleMesh flat_panels(const Pattern& pattern, double h) {
  TriangleMesh mesh;
  PanelMeshOptions options;
  options.edge_length = h;
  for (std::size_t p = 0; p < pattern.panels.size(); ++p) {
    const PanelMesh panel = mesh_panel(pattern.panels[p], options);
    const int offset = int(mesh.vertex_count());
    mesh.positions.resize(mesh.vertex_count() + panel.mesh.vertex_count());
    for (std::size_t t = 0; t < panel.mesh.triangle_count(); ++t) {
      std::array<int, 3> triangle{};
      for (std::size_t c = 0; c < 3; ++c) {
        triangle[c] = panel.mesh.triangles[t][c] + offset;
        const Eigen::Vector2d& uv = panel.mesh.material_uv[t][c];
        mesh.positions[std::size_t(triangle[c])] = Eigen::Vector3d(uv.x(), uv.y(), 0.0);
      }
      mesh.triangles.push_back(triangle);
      mesh.material_uv.push_back(panel.mesh.material_uv[t]);
      mesh.material_ids.push_back(int(p));
    }
  }
  return mesh;
}

const Pattern& tshirt() {
  static const Pattern pattern = read_pattern(samples + "/tshirt.json");
  return pattern;
}

// A different affine map of (u, v) into 3D per panel.
Eigen::Vector3d affine(int panel, const Eigen::Vector2d& uv) {
  const double p = panel;
  return Eigen::Vector3d(0.3 + p, -1.0 + 0.1 * p, 2.0) +
         Eigen::Vector3d(1.0 + p, -0.4, 0.7 * p) * uv.x() +
         Eigen::Vector3d(0.25, 2.0 - p, -1.5) * uv.y();
}

// Smooth, not affine; second derivatives of order one on the panels' metre scale.
Eigen::Vector3d smooth(const Eigen::Vector2d& uv) {
  const double u = uv.x(), v = uv.y();
  return Eigen::Vector3d(std::sin(3.0 * u) * std::cos(2.0 * v), std::exp(u * v),
                         std::cos(u + 2.0 * v) + u * u);
}

template <class Field>
std::vector<Eigen::Vector3d> sample(const TriangleMesh& mesh, const Field& field) {
  const VertexRest rest = vertex_rest_coordinates(mesh);
  std::vector<Eigen::Vector3d> values;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    values.push_back(field(rest.panel[v], rest.uv[v]));
  return values;
}

double largest_error(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  double largest = 0.0;
  for (std::size_t v = 0; v < a.size(); ++v)
    largest = std::max(largest, (a[v] - b[v]).norm());
  return largest;
}

TEST(Prolongation, CarriesAnAffineFieldExactlyOnUnstructuredPanels) {
  const TriangleMesh fine = flat_panels(tshirt(), 0.03);
  for (double h : {0.16, 0.07}) {
    const TriangleMesh coarse = flat_panels(tshirt(), h);
    const Prolongation prolongation(coarse, fine);
    const auto exact = sample(fine, affine);
    const auto carried = prolongation.vertex_field(sample(coarse, affine));
    // Some fine vertices on the curved outlines lie outside the coarse
    // polygon: extrapolated from the nearest triangle, still exact.
    EXPECT_GT(prolongation.largest_outside_distance(), 0.0) << h;
    // The field's values are of order 3: round-off is ~1e-15 of that.
    EXPECT_LT(largest_error(carried, exact), 1e-9) << h;
  }
}

TEST(Prolongation, ConvergesAtSecondOrderForASmoothField) {
  const TriangleMesh fine = flat_panels(tshirt(), 0.01);
  const auto field = [](int, const Eigen::Vector2d& uv) { return smooth(uv); };
  const auto exact = sample(fine, field);
  std::vector<double> errors;
  const std::vector<double> sizes{0.08, 0.04, 0.02};
  for (double h : sizes) {
    const TriangleMesh coarse = flat_panels(tshirt(), h);
    errors.push_back(
        largest_error(Prolongation(coarse, fine).vertex_field(sample(coarse, field)), exact));
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double order = std::log(errors[k - 1] / errors[k]) / std::log(sizes[k - 1] / sizes[k]);
    EXPECT_GE(order, 1.8) << "h " << sizes[k - 1] << " -> " << sizes[k] << ": errors "
                          << errors[k - 1] << ", " << errors[k];
  }
}

TEST(Prolongation, TriangleStateComesFromTheCoarseTriangleHoldingTheCentroid) {
  const TriangleMesh coarse = flat_panels(tshirt(), 0.12);
  const TriangleMesh fine = flat_panels(tshirt(), 0.04);
  const Prolongation prolongation(coarse, fine);
  std::vector<int> index(coarse.triangle_count());
  for (std::size_t t = 0; t < index.size(); ++t)
    index[t] = int(t);
  const std::vector<int> carried = prolongation.triangle_field(index);
  ASSERT_EQ(carried.size(), fine.triangle_count());
  for (std::size_t t = 0; t < fine.triangle_count(); ++t) {
    const std::size_t from = std::size_t(carried[t]);
    EXPECT_EQ(coarse.material_ids[from], fine.material_ids[t]) << t;
    // Independently: the centroid's barycentric coordinates in that coarse
    // triangle, by areas; inside it unless the centroid lies outside the
    // coarse panel (the curved outline), where the nearest triangle serves.
    const auto& f = fine.material_uv[t];
    const Eigen::Vector2d centroid = (f[0] + f[1] + f[2]) / 3.0;
    const auto& c = coarse.material_uv[from];
    const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      return a.x() * b.y() - a.y() * b.x();
    };
    const double area = cross(c[1] - c[0], c[2] - c[0]);
    double smallest = 1.0;
    for (std::size_t k = 0; k < 3; ++k)
      smallest =
          std::min(smallest, cross(c[(k + 1) % 3] - centroid, c[(k + 2) % 3] - centroid) / area);
    if (prolongation.centroid_locations()[t].outside == 0.0) {
      EXPECT_GT(smallest, -1e-9) << t;
    }
  }
}

const Construction& tshirt_construction() {
  static const auto shape = contact::make_mannequin_shape();
  static const BodyDistance distance = [](const Eigen::Vector3d& p, Eigen::Vector3d* gradient) {
    const auto q = shape->query(p);
    if (gradient) *gradient = q.normal;
    return q.distance;
  };
  static const Construction construction = construct(tshirt(), default_mannequin(), distance);
  return construction;
}

TEST(MeshLevels, EdgeLengthsFromTheOptions) {
  const Construction& construction = tshirt_construction();
  LevelOptions options;
  options.target_edge_length = 0.04;
  options.levels = 3;
  EXPECT_EQ(level_edge_lengths(construction, {}, options), (std::vector<double>{0.16, 0.08, 0.04}));
  options.levels = 0;
  options.coarsest_edge_length = 0.12;
  const auto lengths = level_edge_lengths(construction, {}, options);
  ASSERT_EQ(lengths.size(), 3u); // ratios sqrt(3) < 2
  EXPECT_NEAR(lengths[1], std::sqrt(0.12 * 0.04), 1e-12);
  options.coarsest_edge_length = 0.02;
  EXPECT_THROW(level_edge_lengths(construction, {}, options), InputError);
  // Automatic: coarser by halves up to 8 cm while the panels keep 20
  // triangles each on average (the T-shirt's 8 panels: 664 triangles at
  // 8 cm); never fewer than one level.
  options.coarsest_edge_length = 0;
  EXPECT_EQ(level_edge_lengths(construction, {}, options), (std::vector<double>{0.08, 0.04}));
  options.target_edge_length = 0.02;
  EXPECT_EQ(level_edge_lengths(construction, {}, options), (std::vector<double>{0.08, 0.04, 0.02}));
  options.target_edge_length = 0.08;
  EXPECT_EQ(level_edge_lengths(construction, {}, options).size(), 1u);
  options.target_edge_length = 0.04;
  options.min_triangles_per_panel = 1e6;
  EXPECT_EQ(level_edge_lengths(construction, {}, options).size(), 1u);
}

// Each level sews the same lines: the seams pair the same line ids, in the
// same order, each line from the same end point of the pattern to the same
// other one, with vertices no further apart than the level's boundary piece,
// and lines sewn vertex to vertex have as many vertices on both sides.
TEST(MeshLevels, EveryLevelSewsTheSameLines) {
  const Construction& construction = tshirt_construction();
  std::vector<GarmentMesh> levels;
  const std::vector<double> lengths{0.16, 0.08, 0.04};
  for (double h : lengths) {
    PanelMeshOptions options;
    options.edge_length = h;
    levels.push_back(build_garment_mesh(construction, options));
  }
  const auto ends = [](const GarmentMesh& g, const std::vector<int>& line) {
    const VertexRest rest = vertex_rest_coordinates(g.mesh);
    return std::array<Eigen::Vector2d, 2>{rest.uv[std::size_t(line.front())],
                                          rest.uv[std::size_t(line.back())]};
  };
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const GarmentMesh& level = levels[l];
    ASSERT_EQ(level.seams.size(), levels[0].seams.size());
    std::size_t pairs = 0;
    for (std::size_t s = 0; s < level.seams.size(); ++s) {
      const Seam& seam = level.seams[s];
      const Seam& coarsest = levels[0].seams[s];
      EXPECT_EQ(seam.name, coarsest.name);
      EXPECT_EQ(seam.reverse, coarsest.reverse);
      for (const auto& [line, coarse_line] :
           {std::pair{&seam.a, &coarsest.a}, std::pair{&seam.b, &coarsest.b}}) {
        const auto here = ends(level, *line), there = ends(levels[0], *coarse_line);
        for (std::size_t k = 0; k < 2; ++k)
          EXPECT_LT((here[k] - there[k]).norm(), 1e-9) << seam.name;
        const std::vector<double> arc = material_arc_length(level.mesh, *line);
        for (std::size_t i = 1; i < arc.size(); ++i)
          EXPECT_LE(arc[i] - arc[i - 1], boundary_piece_fraction * lengths[l] * (1 + 1e-6))
              << seam.name << " at h = " << lengths[l];
      }
      if (!seam.t_seam) {
        EXPECT_EQ(seam.a.size(), seam.b.size()) << seam.name;
      }
      pairs += seam.a.size() - 1;
    }
    // Halving h doubles the pieces of every line longer than a few pieces.
    if (l > 0) {
      std::size_t coarser_pairs = 0;
      for (const Seam& seam : levels[l - 1].seams)
        coarser_pairs += seam.a.size() - 1;
      EXPECT_GT(double(pairs) / double(coarser_pairs), 1.6);
      EXPECT_LT(double(pairs) / double(coarser_pairs), 2.4);
    }
  }
}

TEST(MeshLevels, ProlongedPlacementClosesItsSeams) {
  const Construction& construction = tshirt_construction();
  PanelMeshOptions coarse_options, fine_options;
  coarse_options.edge_length = 0.16;
  fine_options.edge_length = 0.08;
  const GarmentMesh coarse = build_garment_mesh(construction, coarse_options);
  const GarmentMesh fine = build_garment_mesh(construction, fine_options);
  // The placed garment, carried to the finer level, sewn shut: TAGCON's
  // placement is the same smooth map of both levels' panels.
  std::vector<Eigen::Vector3d> x =
      Prolongation(coarse.mesh, fine.mesh).vertex_field(coarse.mesh.positions);
  // Its seams are open by their placement, and wider than 1 cm somewhere.
  const SeamClosure closure = close_seams(fine.mesh, fine.seams, &x);
  EXPECT_GT(closure.gap_before, 0.01);
  // Vertices sewn vertex to vertex land on the same point; T-seam vertices
  // sewn to an edge move halfway to their partner points.
  double t_seam_gap = 0.0, other_gap = 0.0;
  for (const SeamSpring& spring : seam_springs(fine.mesh, fine.seams, SeamStiffness{1.0})) {
    const double gap = seam_spring_gap(spring, x);
    (spring.to_edge ? t_seam_gap : other_gap) =
        std::max(spring.to_edge ? t_seam_gap : other_gap, gap);
  }
  EXPECT_LT(other_gap, 1e-12);
  EXPECT_LT(closure.gap_after, 0.75 * closure.gap_before);
  EXPECT_EQ(closure.gap_after, std::max(t_seam_gap, other_gap));
}

TEST(MeshLevels, KeepPanelsRenumbersVerticesAndSeams) {
  const Construction& construction = tshirt_construction();
  PanelMeshOptions options;
  options.edge_length = 0.16;
  const GarmentMesh garment = build_garment_mesh(construction, options);
  std::vector<bool> kept(tshirt().panels.size(), true);
  // Without the seams, the last panel (a sleeve's back) can be left out;
  // with them it cannot: a seam would join a panel that is gone.
  GarmentMesh without_seams = garment;
  without_seams.seams.clear();
  kept.back() = false;
  const GarmentMesh smaller = keep_panels(without_seams, kept);
  EXPECT_EQ(smaller.mesh.triangle_count(),
            garment.mesh.triangle_count() - std::size_t(garment.triangle_count.back()));
  EXPECT_EQ(smaller.mesh.vertex_count(), std::size_t(garment.first_vertex.back()));
  EXPECT_THROW(keep_panels(garment, std::vector<bool>(kept.size(), false)), InputError);
}

} // namespace
} // namespace sartor::garment
