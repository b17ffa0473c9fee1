// Shared by sartor wrap and sartor drag (app/wrap_support.hpp).

#include "app/wrap_support.hpp"

#include "common/error.hpp"
#include "common/output.hpp"
#include "contact/body_spec.hpp"

#include <cmath>
#include <sstream>

namespace sartor {

std::vector<OptionSpec> relax_option_specs() {
  const garment::RelaxParameters defaults;
  const auto text = [](double value) {
    std::ostringstream out;
    out << value;
    return out.str();
  };
  return {
      {"offset", "M", text(defaults.offset), "m the cloth's vertices are kept above the body"},
      {"gravity-step", "M", text(defaults.gravity_step),
       "m every free vertex falls per relaxation step (constant speed)"},
      {"friction-limit", "M", text(defaults.friction_limit),
       "m: a shorter downhill move of a vertex touching the body is held by friction"},
      {"max-step", "M", text(defaults.max_step),
       "m: the longest move of a vertex in one relaxation step"},
      {"no-bones", "", "",
       "let cloth edges sweep across the body's bones (its axis or skeleton; "
       "docs/wrapping.md#bones)"},
  };
}

garment::RelaxParameters relax_parameters(const Options& options) {
  garment::RelaxParameters parameters;
  parameters.offset = options.nonnegative_real("offset");
  parameters.gravity_step = options.nonnegative_real("gravity-step");
  parameters.friction_limit = options.nonnegative_real("friction-limit");
  parameters.max_step = options.positive_real("max-step");
  parameters.near_body = std::max(parameters.near_body, parameters.offset);
  if (parameters.far_body <= parameters.near_body) parameters.far_body = 2.0 * parameters.near_body;
  return parameters;
}

std::vector<Bone> relaxation_bones(const Options& options, const std::string& spec,
                                   const contact::Body& body, const std::string& where) {
  if (options.flag("no-bones")) return {};
  std::vector<Bone> bones = contact::body_bones(spec, where);
  for (Bone& bone : bones) {
    bone.start = body.to_world(bone.start, 0.0);
    bone.end = body.to_world(bone.end, 0.0);
  }
  return bones;
}

nlohmann::json bones_summary(const std::vector<Bone>& bones, long held_moves) {
  nlohmann::json names = nlohmann::json::array();
  for (const Bone& bone : bones)
    names.push_back(bone.name);
  return {{"count", bones.size()}, {"names", names}, {"held_moves", held_moves}};
}

void write_body_samples(const std::string& path, const contact::Shape& body,
                        const std::vector<Eigen::Vector3d>& cloth, double spacing) {
  Eigen::Vector3d lower = cloth.front(), upper = cloth.front();
  for (const Eigen::Vector3d& p : cloth) {
    lower = lower.cwiseMin(p);
    upper = upper.cwiseMax(p);
  }
  lower.array() -= 0.1;
  upper.array() += 0.1;
  std::ostringstream out;
  out << "x,y,z\n";
  const Eigen::Vector3d extent = upper - lower;
  const int nx = int(std::ceil(extent.x() / spacing)), ny = int(std::ceil(extent.y() / spacing)),
            nz = int(std::ceil(extent.z() / spacing));
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j)
      for (int k = 0; k <= nz; ++k) {
        const Eigen::Vector3d p = lower + spacing * Eigen::Vector3d(i, j, k);
        const contact::SurfaceQuery query = body.query(p);
        if (std::abs(query.distance) > 0.5 * spacing) continue;
        out << query.closest.x() << "," << query.closest.y() << "," << query.closest.z() << "\n";
      }
  write_file_atomically(path, out.str());
}

} // namespace sartor
