#include "app/cloth_case.hpp"

#include "common/error.hpp"

namespace sartor {

const std::vector<OptionSpec>& case_option_specs() {
  static const std::vector<OptionSpec> all = [] {
    std::vector<OptionSpec> options;
    for (const auto& group : {mesh_option_specs, material_option_specs, load_option_specs,
                              contact_option_specs, seam_option_specs, static_option_specs,
                              time_option_specs, creep_option_specs, certificate_option_specs})
      options.insert(options.end(), group().begin(), group().end());
    return options;
  }();
  return all;
}

ClothCase read_cloth_case(const Options& options, bool generated) {
  ClothCase cloth_case;
  cloth_case.mesh = read_mesh_case(options, generated);
  cloth_case.time = read_time_case(options);
  cloth_case.material = read_material_case(options);
  cloth_case.loads = read_load_case(options);
  cloth_case.statics = read_static_case(options);
  cloth_case.seams = read_seam_case(options);
  cloth_case.contact = read_contact_case(options);
  if (cloth_case.time.creep()) cloth_case.creep = read_creep_case(options);
  cloth_case.certificate = read_certificate_case(options);
  const TimeCase& time = cloth_case.time;
  try {
    if (!time.dynamic() && !time.creep() && options.is_set("pin-release")) {
      throw InputError(
          "option --pin-release: pins let go in time; give --analysis dynamic or creep");
    }
    options.reject_inapplicable("analysis", {"static", "dynamic", "creep"});
  } catch (const InputError& error) {
    cloth_case.inapplicable_option = error.what();
  }
  return cloth_case;
}

} // namespace sartor
