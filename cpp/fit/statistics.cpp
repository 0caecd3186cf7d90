// Linearized statistics of the fit: s^2 = RSS/(n-p), covariance s^2 (J^T J)^-1 (fit.hpp).
#include "statistics.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::fit::internal {

using coatcontact::detail::short_text;

void fill_statistics(const Measurements& data, const std::vector<double>& model_force,
                     const std::vector<std::vector<double>>& jacobian, const std::vector<int>& free_index,
                     const std::vector<double>& inv_sigma, Result& result) {
  coatcontact::detail::GslHandlerOff handler_off;
  const std::size_t n = data.size();
  const std::size_t p_count = free_index.size();
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i) mean += data.force[i] / static_cast<double>(n);
  double rss = 0.0;
  double tss = 0.0;
  result.residual.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    result.residual[i] = model_force[i] - data.force[i];
    rss += result.residual[i] * result.residual[i];
    tss += (data.force[i] - mean) * (data.force[i] - mean);
  }
  result.residual_norm = std::sqrt(rss);
  result.residual_sigma = std::sqrt(rss / static_cast<double>(n - p_count));
  result.r_squared = tss > 0.0 ? 1.0 - rss / tss : (rss == 0.0 ? 1.0 : -HUGE_VAL);
  const bool weighted = !inv_sigma.empty();
  const auto weight = [&](std::size_t i) { return weighted ? inv_sigma[i] : 1.0; };
  result.weighted = weighted;
  result.chi2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) result.chi2 += std::pow(result.residual[i] * weight(i), 2);
  result.chi2_per_dof = result.chi2 / static_cast<double>(n - p_count);

  // Covariance in ln p through the SVD of the column-normalized Jacobian J D^-1:
  // (J^T J)^-1 = D^-1 V S^-2 V^T D^-1.
  std::unique_ptr<gsl_matrix, void (*)(gsl_matrix*)> J(gsl_matrix_alloc(n, p_count), gsl_matrix_free);
  std::vector<double> column_norm(p_count, 0.0);
  for (std::size_t j = 0; j < p_count; ++j) {
    for (std::size_t i = 0; i < n; ++i) column_norm[j] += std::pow(jacobian[j][i] * weight(i), 2);
    column_norm[j] = std::sqrt(column_norm[j]);
    if (!(column_norm[j] > 0.0)) {
      throw NumericalError(std::string("the data do not depend on ") + result.parameters[free_index[j]].name +
                           ": it cannot be fitted (fix it instead)");
    }
    for (std::size_t i = 0; i < n; ++i) gsl_matrix_set(J.get(), i, j, jacobian[j][i] * weight(i) / column_norm[j]);
  }
  std::unique_ptr<gsl_matrix, void (*)(gsl_matrix*)> V(gsl_matrix_alloc(p_count, p_count), gsl_matrix_free);
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> S(gsl_vector_alloc(p_count), gsl_vector_free);
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> work(gsl_vector_alloc(p_count), gsl_vector_free);
  if (gsl_linalg_SV_decomp(J.get(), V.get(), S.get(), work.get()) != GSL_SUCCESS) {
    throw NumericalError("singular value decomposition of the Jacobian failed");
  }
  const double s_max = gsl_vector_get(S.get(), 0);
  const double s_min = gsl_vector_get(S.get(), p_count - 1);
  if (!(s_min > 0.0) || s_max / s_min > kMaximumCondition) {
    throw NumericalError("the free parameters are not identifiable from these data (Jacobian condition "
                         "number " + (s_min > 0.0 ? short_text(s_max / s_min) : std::string("infinite")) +
                         "): fix one of them");
  }
  // Known sigmas: the weights carry the scale. Unknown: the scatter about the fit estimates it.
  const double s2 = weighted ? 1.0 : rss / static_cast<double>(n - p_count);
  std::vector<std::vector<double>> covariance(p_count, std::vector<double>(p_count, 0.0));
  for (std::size_t a = 0; a < p_count; ++a) {
    for (std::size_t b = 0; b < p_count; ++b) {
      double sum = 0.0;
      for (std::size_t k = 0; k < p_count; ++k) {
        const double s = gsl_vector_get(S.get(), k);
        sum += gsl_matrix_get(V.get(), a, k) * gsl_matrix_get(V.get(), b, k) / (s * s);
      }
      covariance[a][b] = s2 * sum / (column_norm[a] * column_norm[b]);
    }
  }
  const std::size_t count = result.value.size();
  result.standard_error.assign(count, 0.0);
  result.correlation.assign(count, std::vector<double>(count, 0.0));
  for (std::size_t a = 0; a < count; ++a) result.correlation[a][a] = 1.0;
  for (std::size_t a = 0; a < p_count; ++a) {
    const int pa = free_index[a];
    // Linearized: se(p) = p se(ln p).
    result.standard_error[pa] = result.value[pa] * std::sqrt(covariance[a][a]);
    for (std::size_t b = 0; b < p_count; ++b) {
      const int pb = free_index[b];
      const double denominator = std::sqrt(covariance[a][a] * covariance[b][b]);
      result.correlation[pa][pb] = denominator > 0.0 ? covariance[a][b] / denominator : (a == b ? 1.0 : 0.0);
    }
  }
  for (int which : free_index) {
    if (!(result.standard_error[which] < result.value[which])) {
      const std::string& name = result.parameters[which].name;
      throw NumericalError("the data do not determine " + name + ": " + name + " = " + short_text(result.value[which]) +
                           " with a standard error of " + short_text(result.standard_error[which]) +
                           " (not smaller than the value)");
    }
  }
  if (!(result.r_squared >= kMinimumRSquared)) {
    throw NumericalError("the model does not describe these data: R^2 = " +
                         short_text(std::max(result.r_squared, -1e6)) + " (the best fit explains less than " +
                         short_text(100.0 * kMinimumRSquared) +
                         " % of the variance of the forces; noise, wrong columns or wrong fixed parameters?)");
  }
}

}  // namespace coatcontact::fit::internal
