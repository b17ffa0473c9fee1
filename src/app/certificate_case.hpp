#pragma once
// The certificate of a case's final state (solvers/certificate.hpp) and, in
// statics, the escape from a saddle: while the certificate finds directions
// of descent, push the state along the lowest mode (the side that lowers
// the energy) and solve again (docs/certificate.md).

#include "app/cli.hpp"
#include "solvers/certificate.hpp"
#include "solvers/statics.hpp"

#include <petscvec.h>

#include <optional>
#include <string>
#include <vector>

namespace sartor {

// The options --no-certificate, --escape-saddles, --saddle-push.
const std::vector<OptionSpec>& certificate_option_specs();

// Those options, read once.
struct CertificateCase {
  bool certify = true;       // not --no-certificate
  long escapes = 3;          // --escape-saddles (statics)
  double saddle_push = 0.01; // --saddle-push, of the starting bounding box's diagonal
};

// Throws InputError naming the option for a malformed value.
CertificateCase read_certificate_case(const Options& options);

struct CertifiedState {
  Certificate certificate;
  int escapes = 0;        // pushes off a saddle
  double push_size = 0.0; // m: the largest vertex displacement of a push
};

// The verdict a run reports on its final state: the certificate's, "skipped"
// (--no-certificate) or "not certified" (nothing to certify: dynamics
// without a settle, creep, a failed solve).
std::string certificate_verdict(const CertificateCase& certificate,
                                const std::optional<CertifiedState>& certified);

// Collective. Certifies x; in statics (`solve` given), while it is a saddle
// and escapes are left, pushes and re-solves, adding the solves' statistics
// to `report` (converged and reason of the last solve).
CertifiedState certify_case(const CertificateCase& certificate, ClothProblem& problem, Vec x,
                            const StaticOptions* solve, StaticReport* report);

} // namespace sartor
