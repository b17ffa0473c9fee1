#include "app/certificate_case.hpp"

#include "fem/petsc_call.hpp"

#include <algorithm>

namespace sartor {

const std::vector<OptionSpec>& certificate_option_specs() {
  static const std::vector<OptionSpec> specs = with_module_prefix(
      {
          {"no-certificate", "", "",
           "skip the certificate of the final state (docs/certificate.md; its stability check "
           "factorises the Hessian twice)"},
          {"escape-saddles", "N", "3",
           "static: when the certificate finds directions of descent (a saddle), push the state "
           "along the lowest mode and solve again, up to N times (0: report the saddle)"},
          {"saddle-push", "R", "0.01",
           "static: the push's largest vertex displacement, relative to the diagonal of the "
           "cloth's starting bounding box"},
      },
      {"certificate"}, {{"no-certificate", "certificate-skip"}});
  return specs;
}

CertificateCase read_certificate_case(const Options& options) {
  CertificateCase certificate;
  certificate.certify = !options.flag("no-certificate");
  certificate.escapes = options.integer_in("escape-saddles", 0, 100);
  certificate.saddle_push = options.nonnegative_real("saddle-push");
  return certificate;
}

std::string certificate_verdict(const CertificateCase& certificate,
                                const std::optional<CertifiedState>& certified) {
  return certified              ? certified->certificate.verdict()
         : !certificate.certify ? "skipped"
                                : "not certified";
}

namespace {

double cloth_size(const TriangleMesh& mesh) {
  if (mesh.positions.empty()) return 0.0;
  Eigen::Vector3d low = mesh.positions.front(), high = low;
  for (const auto& p : mesh.positions) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  return (high - low).norm();
}

void add_solve(const StaticReport& solve, StaticReport* report) {
  report->converged = solve.converged;
  report->reason = solve.reason;
  report->steps.insert(report->steps.end(), solve.steps.begin(), solve.steps.end());
  report->newton_iterations += solve.newton_iterations;
  report->linear_iterations += solve.linear_iterations;
  report->pseudo_steps += solve.pseudo_steps;
  report->final_residual_norm = solve.final_residual_norm;
  report->solve_seconds += solve.solve_seconds;
}

} // namespace

CertifiedState certify_case(const CertificateCase& certificate, ClothProblem& problem, Vec x,
                            const StaticOptions* solve, StaticReport* report) {
  CertifiedState state;
  const CertificateOptions settings;
  const long escapes = solve ? certificate.escapes : 0;
  state.push_size = solve ? certificate.saddle_push * cloth_size(problem.mesh()) : 0.0;
  SartorPetscCall(certify(problem, x, settings, &state.certificate));
  if (!solve || !report->converged || state.push_size <= 0.0) return state;
  Vec saddle = nullptr;
  SartorPetscCall(VecDuplicate(x, &saddle));
  while (state.certificate.saddle() && state.escapes < escapes) {
    SartorPetscCall(VecCopy(x, saddle));
    bool pushed = false;
    SartorPetscCall(push_off_saddle(problem, x, settings, state.push_size, &pushed));
    if (!pushed) break;
    ++state.escapes;
    // Re-solve at the load reached: no ramp, and no cutbacks (the load stays),
    // with the seams as sewn (re-sewing from slack seams would undo the
    // garment and take a long, round-off-sensitive way back).
    StaticOptions again = *solve;
    again.start_load_factor = problem.load_factor;
    again.load_steps = 1;
    again.max_cutbacks = 0;
    again.sewing_stages = 1;
    StaticReport resolved;
    SartorPetscCall(solve_static(problem, x, again, &resolved));
    add_solve(resolved, report);
    if (!resolved.converged) {
      // Back to the saddle, which stays the answer (not converged).
      SartorPetscCall(VecCopy(saddle, x));
      report->converged = false;
      report->final_residual_norm = state.certificate.residual_norm;
      report->reason = "the solve after a push off the saddle failed (" + resolved.reason + ")";
      break;
    }
    SartorPetscCall(certify(problem, x, settings, &state.certificate));
  }
  SartorPetscCall(VecDestroy(&saddle));
  return state;
}

} // namespace sartor
