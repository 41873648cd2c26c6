#pragma once
// Student's t distribution: the quantile that sets a confidence interval of the mean of n
// replicates, mean +- t(1 - alpha/2, n - 1) * sd / sqrt(n). Computed from the regularized
// incomplete beta function, so every degree of freedom is exact, not only a tabulated few.
namespace rupture::server {

/// Regularized incomplete beta function I_x(a, b), for 0 <= x <= 1 and a, b > 0.
double regularizedIncompleteBeta(double x, double a, double b);

/// P(T <= t) for T with `dof` degrees of freedom (dof > 0).
double studentTCdf(double t, double dof);

/// The t with P(T <= t) = p, for 0 < p < 1 and dof > 0 (t(0.975, 2) = 4.303, t(0.975, 9) = 2.262).
double studentTQuantile(double p, double dof);

}  // namespace rupture::server
