#pragma once
// Results of a cloth solve as files a person and ParaView can open:
//   result.h5   HDF5: mesh (triangles, material uv, fabric and panel ids),
//               initial and final positions, displacement, per-triangle
//               strains and tensions; every dataset carries a `units`
//               attribute (docs/formats.md)
//   result.xmf  XDMF description of result.h5 for ParaView, VisIt, meshio
//   final.obj   the deformed cloth with its material coordinates as vt and
//               a group (g) per panel, or per fabric when there are no panels
// and, for time stepping, ClothTimeSeries below.
// Called on one rank with data in mesh numbering (ClothProblem::gather_*).

#include "element/membrane.hpp"
#include "mesh/triangle_mesh.hpp"

#include <chrono>
#include <string>
#include <vector>

namespace sartor {

// What the mesh's numbers stand for, written beside the ids; all optional.
struct ClothOutputLabels {
  std::vector<std::string> fabrics;   // per mesh material id
  std::vector<std::string> panels;    // per panel id
  std::vector<int> panel_of_triangle; // per triangle; empty: no panels
};

// A per-vertex scalar field of the final state beyond positions and
// displacements (contact pressure, friction, seam forces: ClothProblem::
// gather_vertex_loads), written as /fields/NAME with its `units`.
struct ClothNodeField {
  std::string name;
  std::vector<double> values; // per mesh vertex
  std::string units = "1";
};

void write_cloth_results(const std::string& directory, const TriangleMesh& mesh,
                         const std::vector<Eigen::Vector3d>& positions,
                         const std::vector<element::MembraneStrain>& strains,
                         const ClothOutputLabels& labels = {},
                         const std::vector<ClothNodeField>& node_fields = {});

// A time series for ParaView, written state by state (rank 0):
//   series.h5   the mesh (/mesh as in result.h5), then one group per state,
//               /steps/NNNNNN/{time, fields/*, cell_fields/*}
//   series.xmf  a temporal collection of those states, each a uniform grid
//               with its own geometry and, for readers that take the
//               geometry of the first state only (meshio's
//               TimeSeriesReader), the positions as the node field
//               `position`; times as written to 12 significant digits
//               (0.1, not 0.09999999999999999); rewritten after each
//               of the first 100 states, then at most once a second, and when
//               the series closes, so a running or stopped simulation opens
//               as it stands (a killed one without its last second)
class ClothTimeSeries {
public:
  // A per-triangle field beyond the strains and tensions (e.g. creep strains).
  struct CellField {
    std::string name;
    std::vector<double> values; // per mesh triangle
    std::string units = "1";    // the HDF5 attribute `units`
  };
  ClothTimeSeries(const std::string& directory, const TriangleMesh& mesh,
                  const ClothOutputLabels& labels = {});
  // A resumed run's series: keeps the states of the existing series.h5 up
  // to `resumed_time` (s) and drops those after it (written after the
  // checkpoint the run resumes from). An unreadable series.h5 is replaced by
  // a new one, with a warning on stderr.
  ClothTimeSeries(const std::string& directory, const TriangleMesh& mesh,
                  const ClothOutputLabels& labels, double resumed_time);
  // Completes the XDMF index (series.xmf) if the last states are not in it.
  ~ClothTimeSeries();
  ClothTimeSeries(const ClothTimeSeries&) = delete;
  ClothTimeSeries& operator=(const ClothTimeSeries&) = delete;
  // Every state must have the same extra cell fields.
  void write(double time, const std::vector<Eigen::Vector3d>& positions,
             const std::vector<element::MembraneStrain>& strains,
             const std::vector<CellField>& extra_cell_fields = {});
  std::size_t states() const { return times_.size(); }

private:
  void write_index();
  bool keep_states(double last_time);

  std::string directory_;
  const TriangleMesh& mesh_;
  bool has_panels_ = false;
  std::vector<double> times_;
  std::vector<std::string> extra_names_;
  std::string grids_;            // the index's entries, one per state
  std::size_t index_states_ = 0; // states in series.xmf as last written
  std::chrono::steady_clock::time_point index_written_;
};

} // namespace sartor
