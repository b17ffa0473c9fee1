#pragma once
// Quantiles for confidence intervals.

namespace sartor {

// Inverse of the standard normal CDF, to full double precision, 0 < p < 1.
double normal_quantile(double p);

// Inverse of Student's t CDF with `dof` degrees of freedom (Cornish-Fisher
// expansion, A&S 26.7.5: relative error below 1e-4 for dof >= 5).
double student_t_quantile(double p, double dof);

} // namespace sartor
