// Independent reference for kernel tables: int g(q) cos(qu) dq (or sin) over [breaks.front(),
// breaks.back()] by GSL adaptive quadrature, QAWO on each panel (QAG at u = 0), the absolute
// tolerance shared equally between the panels. g must be negligible beyond the last break.
#pragma once
#include <gsl/gsl_integration.h>

#include <vector>

namespace check {

inline double oscillatory_integral(double (*g)(double, void*), void* params, double u, bool sine,
                                   double abs_tol, const std::vector<double>& breaks) {
  gsl_integration_workspace* work = gsl_integration_workspace_alloc(2000);
  double total = 0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = breaks[i], b = breaks[i + 1];
    gsl_function fn{g, params};
    double result = 0, err = 0;
    const double tol = abs_tol / static_cast<double>(breaks.size());
    if (u == 0) {
      if (!sine) gsl_integration_qag(&fn, a, b, tol, 1e-14, 2000, GSL_INTEG_GAUSS41, work, &result, &err);
    } else {
      gsl_integration_qawo_table* table = gsl_integration_qawo_table_alloc(
          u, b - a, sine ? GSL_INTEG_SINE : GSL_INTEG_COSINE, 40);
      gsl_integration_qawo(&fn, a, tol, 1e-14, 2000, work, table, &result, &err);
      gsl_integration_qawo_table_free(table);
    }
    total += result;
  }
  gsl_integration_workspace_free(work);
  return total;
}

}  // namespace check
