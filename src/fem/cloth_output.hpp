#pragma once
// Results of a cloth solve as files a person and ParaView can open:
//   result.h5   HDF5: mesh (triangles, material uv), initial and final
//               positions, displacement, per-triangle strains and tensions
//   result.xmf  XDMF description of result.h5 for ParaView/VisIt
//   final.obj   the deformed cloth with its material coordinates as vt
// and, for time stepping, ClothTimeSeries below.
// Called on one rank with data in mesh numbering (ClothProblem::gather_*).

#include "element/membrane.hpp"
#include "mesh/triangle_mesh.hpp"

#include <string>
#include <vector>

namespace sartor {

void write_cloth_results(const std::string& directory, const TriangleMesh& mesh,
                         const std::vector<Eigen::Vector3d>& positions,
                         const std::vector<element::MembraneStrain>& strains);

// A time series for ParaView, written state by state (rank 0):
//   series.h5   the mesh (/mesh as in result.h5), then one group per state,
//               /steps/NNNNNN/{time, fields/*, cell_fields/*}
//   series.xmf  a temporal collection of those states; rewritten after each
//               state, so a running or stopped simulation opens as it stands
class ClothTimeSeries {
public:
  // A per-triangle field beyond the strains and tensions (e.g. creep strains).
  struct CellField {
    std::string name;
    std::vector<double> values; // per mesh triangle
  };
  ClothTimeSeries(const std::string& directory, const TriangleMesh& mesh);
  // Every state must have the same extra cell fields.
  void write(double time, const std::vector<Eigen::Vector3d>& positions,
             const std::vector<element::MembraneStrain>& strains,
             const std::vector<CellField>& extra_cell_fields = {});
  std::size_t states() const { return times_.size(); }

private:
  std::string directory_;
  const TriangleMesh& mesh_;
  std::vector<double> times_;
  std::vector<std::string> extra_names_;
};

} // namespace sartor
