#pragma once
// Quantiles for confidence intervals (Boost.Math, to double precision).

namespace sartor {

// Inverse of the standard normal CDF, to full double precision, 0 < p < 1.
double normal_quantile(double p);

// Inverse of Student's t CDF with `dof` degrees of freedom, 0 < p < 1.
double student_t_quantile(double p, double dof);

} // namespace sartor
