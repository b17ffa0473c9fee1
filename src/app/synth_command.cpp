// sartor synth: a synthetic creep-and-recovery "measurement" with known
// parameters and a documented noise model, for testing and demonstrating fits.

#include "app/commands.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/petsc_call.hpp"
#include "material/creep_recovery_model.hpp"
#include "material/fabric.hpp"
#include "solvers/creep_fit.hpp"

#include <petscsys.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>

namespace sartor {

const CommandSpec& synth_command() {
  static const CommandSpec spec{
      "synth",
      "synthetic creep-and-recovery measurement with known parameters and noise",
      "sartor synth [--fabric PRESET:DIR] [--samples N] [--noise SD] [--output FILE.csv]",
      "Samples the constant-force creep-and-recovery response of one fabric direction\n"
      "at N equally spaced times over loading + recovery and adds independent Gaussian\n"
      "noise of standard deviation SD to the strain (Box-Muller on a 64-bit Mersenne\n"
      "Twister seeded with --seed, so files are reproducible). The file is labelled\n"
      "synthetic in its header and reads back with `sartor fit`. With --load-history\n"
      "the load is that history (ramps, several levels, cycles), the creep law\n"
      "integrated exactly through it, with the elastic secant at its peak tension.",
      {
          {"fabric", "SPEC", "cotton_twill:warp",
           "one fabric direction: preset:dir or FILE.yaml:dir"},
          {"force", "N", "196.133", "test force (20 kgf)"},
          {"width", "M", "0.08", "strip width, m"},
          {"tension", "N/M", "", "test tension per unit width, N/m (instead of force/width)"},
          {"load-duration", "S", "3600", "loading time, s"},
          {"recovery-duration", "S", "3600", "recovery time, s"},
          {"samples", "N", "86400", "number of samples (equally spaced from t = 0)"},
          {"noise", "SD", "2e-4", "standard deviation of the additive strain noise"},
          {"seed", "N", "1", "random seed"},
          {"load-history", "FILE", "",
           "any piecewise-linear load (time and tension, or force over --width) instead of the "
           "constant-force test; the samples span its first to its last row"},
          {"output", "FILE", "synthetic_creep.csv", "output CSV file"},
      },
      0};
  return spec;
}

namespace {

// Standard normal deviates from a fixed generator: the same on every platform
// (std::normal_distribution is not).
class GaussianNoise {
public:
  explicit GaussianNoise(unsigned long long seed) : generator_(seed) {}
  double next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double scale = 1.0 / 18446744073709551616.0; // 2^-64
    const double u1 = (double(generator_()) + 0.5) * scale;
    const double u2 = (double(generator_()) + 0.5) * scale;
    const double radius = std::sqrt(-2.0 * std::log(u1));
    spare_ = radius * std::sin(2.0 * M_PI * u2);
    has_spare_ = true;
    return radius * std::cos(2.0 * M_PI * u2);
  }

private:
  std::mt19937_64 generator_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

// --load-history's knots; empty without it (the constant-tension test).
LoadHistory synth_load_history(const Options& options) {
  LoadHistory history;
  if (options.is_set("load-history")) {
    for (const char* other : {"tension", "force", "load-duration", "recovery-duration"}) {
      if (options.is_set(other)) {
        throw InputError("option --load-history gives the load; drop --" + std::string(other));
      }
    }
    history = read_load_history_file(options.text("load-history"),
                                     options.is_set("width")
                                         ? std::optional<double>(options.positive_real("width"))
                                         : std::nullopt);
  }
  return history;
}

// The creep test's parameters of the material at `tension`: for a single
// load level any tension-strain curve acts through its secant.
CreepTestParameters secant_parameters(const DirectionalMaterial& material, double tension) {
  CreepTestParameters parameters;
  parameters.elastic_modulus = tension / material.elastic.strain_at_tension(tension);
  parameters.creep_modulus = material.creep.creep_modulus;
  parameters.alpha = material.creep.alpha;
  parameters.lambda_load = material.creep.lambda_load;
  parameters.lambda_unload = material.creep.lambda_unload;
  return parameters;
}

} // namespace

int run_synth(const Invocation& invocation) {
  const Options& options = invocation.options;
  const auto choices = resolve_fabrics(options.text("fabric"));
  choices.front().fabric.check_creep();
  if (choices.size() != 1) {
    throw InputError("option --fabric: synth needs one direction, e.g. " + choices.front().label());
  }
  const MaterialChoice& choice = choices.front();
  if (options.is_set("tension") && (options.is_set("force") || options.is_set("width"))) {
    throw InputError("give --tension or --force with --width, not both");
  }
  const LoadHistory history = synth_load_history(options);
  double tension = 0.0; // of the test, or the history's peak (the elastic secant's)
  if (history.empty()) {
    tension = options.is_set("tension")
                  ? options.positive_real("tension")
                  : options.positive_real("force") / options.positive_real("width");
  }
  for (const LoadKnot& knot : history)
    tension = std::max(tension, knot.tension);
  if (!(tension > 0.0)) {
    throw InputError("option --load-history: the tension of " + options.text("load-history") +
                     " is never positive");
  }
  const double load_duration = options.positive_real("load-duration");
  const double recovery_duration = options.positive_real("recovery-duration");
  // At most 1e7 rows (some 300 MB of CSV).
  const long samples = options.integer_in("samples", 10, 10'000'000);
  const double noise = options.nonnegative_real("noise");
  const long seed = options.integer("seed");

  const DirectionalMaterial& material = choice.material();
  const CreepTestParameters parameters = secant_parameters(material, tension);
  const CreepTest test{tension, 0.0, load_duration};

  const double start = history.empty() ? 0.0 : history.front().time;
  const double duration =
      history.empty() ? load_duration + recovery_duration : history.back().time - start;
  if (!(duration > 0.0)) {
    throw InputError("option --load-history: " + options.text("load-history") +
                     " must span a positive time");
  }
  std::vector<double> times(static_cast<std::size_t>(samples));
  for (long i = 0; i < samples; ++i)
    times[std::size_t(i)] = start + double(i) * duration / double(samples);
  std::vector<double> strain(times.size());
  if (history.empty()) {
    evaluate_creep_test(test, parameters, times.data(), times.size(), strain.data());
  } else {
    evaluate_load_history(history, parameters, times.data(), times.size(), 0, strain.data());
  }
  GaussianNoise gaussian(static_cast<unsigned long long>(seed));

  std::ostringstream out;
  out << "# SYNTHETIC creep-and-recovery data generated by sartor synth " << SARTOR_VERSION
      << " (not a measurement)\n"
      << "# fabric " << choice.label() << " (" << choice.fabric.source << ")\n"
      << "# parameters: elastic_modulus_N_per_m=" << format_number(parameters.elastic_modulus)
      << " E_N_per_m=" << format_number(parameters.creep_modulus)
      << " alpha=" << format_number(parameters.alpha)
      << " lambda_load_per_s=" << format_number(parameters.lambda_load)
      << " lambda_unload_per_s=" << format_number(parameters.lambda_unload) << "\n"
      << (history.empty() ? "# test: tension " + format_number(tension) +
                                " N/m applied at t = 0 s, removed at t = " +
                                format_number(load_duration) + " s\n"
                          : "# test: load history " + options.text("load-history") + " (" +
                                std::to_string(history.size()) + " rows, peak " +
                                format_number(tension) + " N/m; elastic secant at the peak)\n")
      << "# noise: strain + N(0, " << format_number(noise) << "^2), independent, seed " << seed
      << " (Box-Muller on mt19937_64)\n"
      << "time_s,tension_N_per_m,strain\n";
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double applied = history.empty()
                               ? (test.phase(times[i]) == TestPhase::loading ? tension : 0.0)
                               : tension_at(history, times[i]);
    out << format_number(times[i]) << ',' << format_number(applied) << ','
        << format_number(strain[i] + noise * gaussian.next()) << '\n';
  }
  const std::string path = options.text("output");
  if (is_root()) {
    const auto parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) make_output_directory(parent.string());
    write_file_atomically(path, out.str());
  }
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "sartor synth: wrote %s (%ld samples of %s)\n",
                              path.c_str(), samples, choice.label().c_str()));
  return 0;
}

} // namespace sartor
