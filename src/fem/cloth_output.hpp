#pragma once
// Results of a cloth solve as files a person and ParaView can open:
//   result.h5   HDF5: mesh (triangles, material uv), initial and final
//               positions, displacement, per-triangle strains and tensions
//   result.xmf  XDMF description of result.h5 for ParaView/VisIt
//   final.obj   the deformed cloth with its material coordinates as vt
// Called on one rank with data in mesh numbering (ClothProblem::gather_*).

#include "element/membrane.hpp"
#include "mesh/triangle_mesh.hpp"

#include <string>
#include <vector>

namespace sartor {

void write_cloth_results(const std::string& directory, const TriangleMesh& mesh,
                         const std::vector<Eigen::Vector3d>& positions,
                         const std::vector<element::MembraneStrain>& strains);

} // namespace sartor
