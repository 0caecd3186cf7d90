// Library-private pieces shared by the AFM curve fits (afm_curve_model.cpp: Hertz/Sneddon;
// afm_adhesive_model.cpp: JKR through the cantilever). Not installed.
#pragma once
#include <string>
#include <vector>

#include "coatcontact/afm_fit.hpp"

namespace coatcontact::fit::internal {

// s^2 (J^T J)^-1 on the column-scaled normal matrix: the standard errors of the columns'
// parameters; NumericalError if a column is zero or the matrix singular.
std::vector<double> afm_standard_errors(const std::vector<std::vector<double>>& columns, double sigma);

// From r.model_force and r.indentation (filled): residuals (model - data), rss, points in
// contact (indentation > contact_threshold; none: NumericalError "afm fit: " + no_contact),
// max indentation, residual sigma, R^2, and chi2 when noise_sigma > 0.
void afm_residual_statistics(AfmFitResult& r, const std::vector<double>& force, double noise_sigma, int free_count,
                             double contact_threshold, const std::string& no_contact);

// The least-squares step x minimizing |J x - residual| (J by columns; SVD, tiny singular values dropped).
std::vector<double> afm_least_squares_step(const std::vector<std::vector<double>>& columns, const std::vector<double>& residual);

// The JKR fit through the cantilever (problem.model == kJkr) and its model force at z.
AfmFitResult afm_fit_jkr(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                         int free_count);
std::vector<double> afm_jkr_model_force(const AfmFitProblem& problem, const std::vector<double>& z);
// Tabor's mu and Maugis's lambda of the estimates in r (reduced_modulus, work), and the warning
// when lambda is below kJkrMinimumLambda.
void afm_jkr_lambda(const AfmFitProblem& problem, AfmFitResult& r);

}  // namespace coatcontact::fit::internal
