// Seam lines and their springs (mesh/seams.hpp), the seam file, the tube
// panels generator and the exact merge of sewn vertices.

#include "common/error.hpp"
#include "mesh/merge.hpp"
#include "mesh/panels.hpp"
#include "mesh/seams.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numeric>
#include <random>

namespace sartor {
namespace {

const double width = 0.4, height = 0.3;

double total_stiffness(const std::vector<SeamSpring>& springs, int seam) {
  double sum = 0.0;
  for (const SeamSpring& s : springs)
    sum += s.seam == seam ? s.stiffness : 0.0;
  return sum;
}

TEST(SeamLines, TubePanelsAreTwoRectanglesWithTwoSideSeams) {
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 8, 6, 10, 4, 0.15);
  EXPECT_EQ(tube.mesh.vertex_count(), std::size_t(9 * 7 + 11 * 5));
  EXPECT_EQ(tube.mesh.triangle_count(), std::size_t(2 * (8 * 6 + 10 * 4)));
  ASSERT_EQ(tube.seams.size(), 2u);
  EXPECT_NO_THROW(check_seams(tube.mesh, tube.seams, "tube"));
  for (const Seam& seam : tube.seams) {
    EXPECT_NEAR(material_arc_length(tube.mesh, seam.a).back(), height, 1e-14);
    EXPECT_NEAR(material_arc_length(tube.mesh, seam.b).back(), height, 1e-14);
    EXPECT_FALSE(seam_is_matched(tube.mesh, seam)); // 6 against 4 rows
    // Seam lines start the gap apart.
    EXPECT_NEAR((tube.mesh.positions[std::size_t(seam.a.front())] -
                 tube.mesh.positions[std::size_t(seam.b.front())])
                    .norm(),
                0.15, 1e-12);
  }
}

TEST(SeamLines, MatchedLinesGiveVertexToVertexSpringsOfTheSeamStiffness) {
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 8, 6, 10, 6, 0.1);
  SeamStiffness stiffness;
  stiffness.modulus = 30000.0;
  const auto springs = seam_springs(tube.mesh, tube.seams, stiffness);
  ASSERT_EQ(springs.size(), std::size_t(2 * 7));
  for (const SeamSpring& s : springs)
    EXPECT_FALSE(s.to_edge);
  // kappa = penalty E / h, h = height / 6; the springs add up to kappa * height.
  const double kappa = 100.0 * 30000.0 / (height / 6);
  EXPECT_NEAR(total_stiffness(springs, 0), kappa * height, 1e-9 * kappa * height);
  EXPECT_NEAR(total_stiffness(springs, 1), kappa * height, 1e-9 * kappa * height);
  // An explicit kappa and a certainty.
  auto uncertain = tube.seams;
  uncertain[1].certainty = 0.5;
  stiffness.per_length = 2e6;
  const auto weak = seam_springs(tube.mesh, uncertain, stiffness);
  EXPECT_NEAR(total_stiffness(weak, 0), 2e6 * height, 1e-6);
  EXPECT_NEAR(total_stiffness(weak, 1), 1e6 * height, 1e-6);
}

TEST(SeamLines, UnequalLinesGiveVertexToEdgeSpringsAtTheSameArcLength) {
  // With no gap both seam lines lie on the same straight segment, so every
  // anchor at the same normalised arc length is exactly where its vertex is.
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 8, 6, 10, 4, 0.0);
  SeamStiffness stiffness;
  stiffness.modulus = 30000.0;
  const auto springs = seam_springs(tube.mesh, tube.seams, stiffness);
  int to_edge = 0;
  for (const SeamSpring& s : springs)
    to_edge += s.to_edge ? 1 : 0;
  EXPECT_GT(to_edge, 0);
  EXPECT_LT(largest_seam_gap(springs, tube.mesh.positions), 1e-14);
  // Each line emits half the seam's stiffness: kappa (height + height) / 2.
  const double kappa = 100.0 * 30000.0 / (2 * height / 10);
  EXPECT_NEAR(total_stiffness(springs, 0), kappa * height, 1e-9 * kappa * height);
  // Moving one panel opens every spring by the same amount.
  auto moved = tube.mesh.positions;
  for (std::size_t v = std::size_t(tube.panel_start[1]); v < moved.size(); ++v)
    moved[v].y() += 0.02;
  EXPECT_NEAR(largest_seam_gap(springs, moved), 0.02, 1e-14);
}

TEST(SeamLines, ReversedLinePairsStartWithEnd) {
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 4, 5, 4, 3, 0.1);
  auto reversed = tube.seams;
  for (Seam& seam : reversed) {
    std::reverse(seam.b.begin(), seam.b.end());
    seam.reverse = true;
  }
  SeamStiffness stiffness;
  stiffness.modulus = 1000.0;
  const auto original = seam_springs(tube.mesh, tube.seams, stiffness);
  const auto same = seam_springs(tube.mesh, reversed, stiffness);
  ASSERT_EQ(original.size(), same.size());
  EXPECT_NEAR(largest_seam_gap(same, tube.mesh.positions),
              largest_seam_gap(original, tube.mesh.positions), 1e-14);
}

// The springs' exact changes with the material coordinates (AutoDiff
// through the construction) against central differences of springs built
// on moved coordinates: matched lines (stiffness only) and unequal ones
// (vertex-to-edge springs: stiffness and edge parameter), with the
// automatic kappa and with a given one.
TEST(SeamLines, SpringChangesMatchDifferencesOfSpringsOnMovedPatterns) {
  for (const int rows_b : {6, 4}) {
    const mesh::PanelMesh tube = mesh::tube_panels(width, height, 8, 6, 10, rows_b, 0.1);
    // One random (u, v) change per vertex, the same for all its corners.
    std::mt19937_64 random(13);
    std::uniform_real_distribution<double> jitter(-0.005, 0.005);
    std::vector<Eigen::Vector2d> per_vertex(tube.mesh.vertex_count());
    for (auto& d : per_vertex)
      d = {jitter(random), jitter(random)};
    MaterialChange change(tube.mesh.triangle_count());
    for (std::size_t t = 0; t < change.size(); ++t) {
      for (std::size_t c = 0; c < 3; ++c)
        change[t][c] = per_vertex[std::size_t(tube.mesh.triangles[t][c])];
    }
    const auto moved = [&](double scale) {
      TriangleMesh m = tube.mesh;
      for (std::size_t t = 0; t < change.size(); ++t) {
        for (std::size_t c = 0; c < 3; ++c)
          m.material_uv[t][c] += scale * change[t][c];
      }
      return m;
    };
    for (const double per_length : {0.0, 2e6}) {
      SeamStiffness stiffness;
      stiffness.modulus = 30000.0;
      stiffness.per_length = per_length;
      const auto exact = seam_spring_changes(tube.mesh, tube.seams, stiffness, change);
      const double h = 1e-5; // times up to 5 mm: 50 nm
      const TriangleMesh up_mesh = moved(h), down_mesh = moved(-h);
      const auto up = seam_springs(up_mesh, tube.seams, stiffness);
      const auto down = seam_springs(down_mesh, tube.seams, stiffness);
      ASSERT_EQ(exact.size(), up.size());
      ASSERT_EQ(down.size(), up.size());
      double largest_stiffness_change = 0.0, largest_s_change = 0.0;
      for (std::size_t i = 0; i < exact.size(); ++i) {
        const double d_stiffness = (up[i].stiffness - down[i].stiffness) / (2.0 * h);
        const double d_s = (up[i].s - down[i].s) / (2.0 * h);
        EXPECT_NEAR(exact[i].stiffness, d_stiffness, 1e-6 * std::abs(up[i].stiffness)) << i;
        EXPECT_NEAR(exact[i].s, d_s, 1e-6) << i;
        largest_stiffness_change = std::max(largest_stiffness_change, std::abs(exact[i].stiffness));
        largest_s_change = std::max(largest_s_change, std::abs(exact[i].s));
      }
      EXPECT_GT(largest_stiffness_change, 0.0);
      if (rows_b == 4) { // vertex-to-edge springs slide
        EXPECT_GT(largest_s_change, 0.0);
      }
    }
  }
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = std::string(SARTOR_SEAM_TEST_OUT) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

void expect_seam_file_error(const std::string& name, const std::string& text,
                            const std::string& expected) {
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 2, 2, 2, 2, 0.1);
  const std::string path = write_file(name, text);
  try {
    read_seams(path, tube.mesh);
    ADD_FAILURE() << name << ": no error";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

TEST(SeamFile, RoundTripsAndReportsBadInputWithFileAndSeam) {
  // Tube 2x2 + 2x2: back panel vertices 0..8, front 9..17.
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 2, 2, 2, 2, 0.1);
  const std::string path = std::string(SARTOR_SEAM_TEST_OUT) + "/tube_seams.json";
  write_seams(path, tube.seams);
  const auto read = read_seams(path, tube.mesh);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[1].name, "left");
  EXPECT_EQ(read[1].a, tube.seams[1].a);
  EXPECT_EQ(read[1].b, tube.seams[1].b);

  const std::string good = R"({"name": "ok", "a": [2, 5, 8], "b": [9, 12, 15]})";
  expect_seam_file_error("syntax.json", R"({"seams": [{"a": [1, 2,]}]})", "not valid JSON");
  expect_seam_file_error("unknown_vertex.json",
                         R"({"seams": [)" + good +
                             R"(, {"name": "x", "a": [2, 99], "b": [9, 12]}]})",
                         "seam 1 ('x'): line a: vertex 99 is not in the mesh (0..17)");
  expect_seam_file_error("one_vertex.json", R"({"seams": [{"a": [2], "b": [9, 12]}]})",
                         "seam 0 ('seam 0'): line a has 1 vertex(es)");
  expect_seam_file_error("interior.json", R"({"seams": [{"a": [3, 4], "b": [9, 12]}]})",
                         "edge 3-4 is not on a panel boundary");
  expect_seam_file_error("not_joined.json", R"({"seams": [{"a": [2, 8], "b": [9, 12]}]})",
                         "vertices 2 and 8 are not joined by a mesh edge");
  expect_seam_file_error("unknown_key.json",
                         R"({"seams": [{"a": [2, 5], "b": [9, 12], "revers": true}]})",
                         "seam 0: unknown key 'revers'");
  expect_seam_file_error("certainty.json",
                         R"({"seams": [{"a": [2, 5], "b": [9, 12], "certainty": 0}]})",
                         "certainty must lie in (0, 1]");
  expect_seam_file_error("no_list.json", R"({"seam": []})", "expected an object {\"seams\"");
  expect_seam_file_error(
      "t_seam_on_boundary.json", R"({"seams": [{"a": [2, 5], "b": [9, 12], "t_seam": true}]})",
      "line b: edge 9-12 of a T-seam is not inside a panel (it has 1 triangles)");
  expect_seam_file_error("t_seam_flag.json",
                         R"({"seams": [{"a": [2, 5], "b": [3, 4], "t_seam": 1}]})",
                         "'t_seam' must be true or false");
}

// A T-seam sews a boundary line onto a line inside a panel (a patch pocket
// onto its placement line): line b runs on interior edges, the springs pull
// line a's vertices onto it, and it round-trips through the seam file. It
// cannot be merged: the merged edges would join three triangles.
TEST(SeamFile, TSeamRunsInsideAPanel) {
  // Tube 2x2 + 2x2: back panel vertices 0..8 (4 the centre), front 9..17.
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 2, 2, 2, 2, 0.1);
  const std::string path =
      write_file("t_seam.json",
                 R"({"seams": [{"name": "pocket", "a": [9, 12], "b": [3, 4], "t_seam": true}]})");
  const std::vector<Seam> seams = read_seams(path, tube.mesh);
  ASSERT_EQ(seams.size(), 1u);
  EXPECT_TRUE(seams[0].t_seam);
  write_seams(path, seams);
  EXPECT_TRUE(read_seams(path, tube.mesh).at(0).t_seam);
  SeamStiffness stiffness;
  stiffness.modulus = 30000.0;
  const auto springs = seam_springs(tube.mesh, seams, stiffness);
  ASSERT_EQ(springs.size(), 2u); // vertex to vertex: two segments of equal length
  EXPECT_EQ(springs[0].vertices[1], 3);
  EXPECT_EQ(springs[1].vertices[1], 4);
  try {
    matched_vertex_pairs(tube.mesh, seams);
    ADD_FAILURE() << "a T-seam was merged";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("seam 0 ('pocket'): a T-seam cannot be merged"),
              std::string::npos)
        << error.what();
  }
}

TEST(SeamMerge, MatchedSeamsMergeIntoOneConnectedTube) {
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 6, 4, 6, 4, 0.0);
  const auto pairs = matched_vertex_pairs(tube.mesh, tube.seams);
  EXPECT_EQ(pairs.size(), std::size_t(2 * 5));
  const MergedMesh merged = merge_vertices(tube.mesh, pairs);
  EXPECT_EQ(merged.mesh.vertex_count(), tube.mesh.vertex_count() - 2 * 5);
  EXPECT_EQ(merged.mesh.triangle_count(), tube.mesh.triangle_count());
  // The seam edges became interior edges with bending hinges: 2 seams x 4 edges.
  EXPECT_EQ(interior_edges(merged.mesh).size(), interior_edges(tube.mesh).size() + 2 * 4);
  // A closed tube: its boundary is the two rims, 2 x 12 vertices.
  EXPECT_EQ(boundary_vertices(merged.mesh).size(), std::size_t(2 * 12));
  // One connected piece: walk the triangles' vertex graph.
  std::vector<int> component(merged.mesh.vertex_count());
  std::iota(component.begin(), component.end(), 0);
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& t : merged.mesh.triangles) {
      const int lowest = std::min({component[std::size_t(t[0])], component[std::size_t(t[1])],
                                   component[std::size_t(t[2])]});
      for (int v : t) {
        if (component[std::size_t(v)] != lowest) {
          component[std::size_t(v)] = lowest;
          changed = true;
        }
      }
    }
  }
  for (int c : component)
    EXPECT_EQ(c, 0);
  // Both panels keep their own material coordinates.
  EXPECT_EQ(merged.mesh.material_uv.size(), tube.mesh.material_uv.size());
}

TEST(SeamMerge, UnequalSeamsCannotBeMerged) {
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 6, 4, 6, 3, 0.0);
  EXPECT_THROW(matched_vertex_pairs(tube.mesh, tube.seams), InputError);
}

} // namespace
} // namespace sartor
