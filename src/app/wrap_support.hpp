#pragma once
// What `sartor wrap` and `sartor drag` share: the relaxation's options, the
// body samples their pictures draw, and CPU time (docs/wrapping.md).

#include "app/cli.hpp"
#include "contact/shape.hpp"
#include "garment/wrap_relax.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sartor {

// --offset, --gravity-step, --friction-limit, --max-step, --no-bones.
std::vector<OptionSpec> relax_option_specs();
// Throws InputError naming the option for a value out of range.
garment::RelaxParameters relax_parameters(const Options& options);

// The bones of the body `spec` describes (contact::body_bones) where `body`
// is at time 0, or none with --no-bones. `where` names the specification.
std::vector<Bone> relaxation_bones(const Options& options, const std::string& spec,
                                   const contact::Body& body, const std::string& where);
// {"count", "names", "held_moves"} for wrap.json and drag.json.
nlohmann::json bones_summary(const std::vector<Bone>& bones, long held_moves);

// DIRECTORY/body_points.csv (x,y,z): body surface points around the cloth
// (within 0.1 m of its bounding box, about `spacing` apart), for the picture.
void write_body_samples(const std::string& path, const contact::Shape& body,
                        const std::vector<Eigen::Vector3d>& cloth, double spacing);

} // namespace sartor
