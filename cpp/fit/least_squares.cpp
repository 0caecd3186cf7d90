// Nonlinear least squares of the force residuals (GSL gsl_multifit_nlinear, trust region).
#include "least_squares.hpp"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"
#include "trust_region.hpp"

namespace coatcontact::fit::internal {
namespace {

struct FitContext {
  const Measurements* data;
  Model* model;
  std::vector<int> free_index;  // parameter index of each GSL variable
  Parameters start;
  std::vector<double> scale;  // per point: 1/sigma_eff, or 1/max|F| when unweighted
  // |F_model - F| below which a residual is the model's own noise [N]: the interpolant's values
  // are accurate to the solver tolerance relative to the forces.
  double noise_floor = 0.0;

  Parameters parameters(const gsl_vector* x) const {
    Parameters value = start;
    for (std::size_t j = 0; j < free_index.size(); ++j) {
      value.values[free_index[j]] = start.values[free_index[j]] * std::exp(gsl_vector_get(x, j) - kLogOffset);
    }
    return value;
  }
};

void residuals(const FitContext& ctx, const gsl_vector* x, gsl_vector* f) {
  const ModelAtData m = ctx.model->at_data(ctx.parameters(x));
  for (std::size_t i = 0; i < ctx.data->size(); ++i) {
    gsl_vector_set(f, i, (m.force[i] - ctx.data->force[i]) * ctx.scale[i]);
  }
}

void jacobian(const FitContext& ctx, const gsl_vector* x, gsl_matrix* J) {
  const Parameters p = ctx.parameters(x);
  const ModelAtData m = ctx.model->at_data(p);
  const auto columns = ctx.model->force_derivatives(p, m, ctx.free_index);
  for (std::size_t j = 0; j < columns.size(); ++j) {
    for (std::size_t i = 0; i < columns[j].size(); ++i) {
      gsl_matrix_set(J, i, j, columns[j][i] * ctx.scale[i]);
    }
  }
}

std::string estimates_text(const FitContext& ctx, const std::vector<double>& x) {
  std::vector<double> value = ctx.start.values;
  for (std::size_t j = 0; j < ctx.free_index.size(); ++j) {
    value[ctx.free_index[j]] = ctx.start.values[ctx.free_index[j]] * std::exp(x[j] - kLogOffset);
  }
  std::string text;
  for (int which : ctx.free_index) {
    if (!text.empty()) text += ", ";
    text += ctx.model->names()[which].name + " = " + coatcontact::detail::short_text(value[which]);
  }
  return text;
}

// One trust-region solve (Levenberg-Marquardt steps, More scaling, QR) over ctx.free_index.
struct Stage {
  int status = GSL_FAILURE;
  int info = 0;
  int iterations = 0;
  std::vector<double> x;  // GSL variables at the end
  Parameters values;
  double cost = 0.0;
  bool gradient_small = false;  // for GSL_ENOPROG
  bool residuals_at_noise_floor = false;  // every |F_model - F| <= noise_floor (exact data)
};

Stage run_stage(FitContext& ctx, int max_iterations) {
  const std::size_t n = ctx.data->size();
  const std::size_t p_count = ctx.free_index.size();
  TrustRegion region(
      n, p_count, [&ctx](const gsl_vector* x, gsl_vector* f) { residuals(ctx, x, f); },
      [&ctx](const gsl_vector* x, gsl_matrix* J) { jacobian(ctx, x, J); });
  if (!region.start()) throw NumericalError("could not evaluate the model at the start values");
  const double xtol = 1e-10;  // relative change of each parameter ~ xtol * kLogOffset = 1e-9
  const double gtol = 1e-10;
  const double ftol = 0.0;
  Stage stage;
  stage.status = region.run(max_iterations, xtol, gtol, ftol, &stage.info);
  stage.iterations = region.iterations();
  const gsl_vector* x = region.position();
  for (std::size_t j = 0; j < p_count; ++j) stage.x.push_back(gsl_vector_get(x, j));
  stage.values = ctx.parameters(x);
  const gsl_vector* f_end = region.residual();
  stage.cost = gsl_blas_dnrm2(f_end) * gsl_blas_dnrm2(f_end);
  if (stage.status == GSL_ENOPROG || stage.status == GSL_EMAXITER) {
    // No step decreases the cost any more: accept only if the gradient is at the noise level
    // of the model (the interpolated values carry relative noise ~ solver tolerance).
    const gsl_vector* f = region.residual();
    const gsl_matrix* J = region.jacobian();
    const double f_norm = gsl_blas_dnrm2(f);
    // Data without noise: the residuals are the interpolant's own rounding, their direction is
    // random, and the gradient test cannot pass; the fit is then as good as the model allows.
    stage.residuals_at_noise_floor = true;
    for (std::size_t i = 0; i < n; ++i) {
      if (std::fabs(gsl_vector_get(f, i)) > ctx.noise_floor * ctx.scale[i]) stage.residuals_at_noise_floor = false;
    }
    stage.gradient_small = true;
    for (std::size_t j = 0; j < p_count; ++j) {
      double g = 0.0;
      double column_norm = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        g += gsl_matrix_get(J, i, j) * gsl_vector_get(f, i);
        column_norm += gsl_matrix_get(J, i, j) * gsl_matrix_get(J, i, j);
      }
      if (std::fabs(g) > 1e-6 * std::sqrt(column_norm) * f_norm) stage.gradient_small = false;
    }
  }
  return stage;
}

}  // namespace

Minimum minimize(Model& model, const Problem& problem, const std::vector<int>& free_index,
                 const Parameters& start, const std::vector<double>& scale, bool fit_work_first) {
  coatcontact::detail::GslHandlerOff handler_off;
  FitContext ctx;
  ctx.data = &model.data();
  ctx.model = &model;
  ctx.free_index = free_index;
  ctx.start = start;
  ctx.scale = scale;
  double largest_force = 0.0;
  for (double f : model.data().force) largest_force = std::max(largest_force, std::fabs(f));
  ctx.noise_floor = problem.solver_tolerance * largest_force;

  Minimum result;
  // With several free parameters, w alone is fitted first (a 1-D problem that always has a
  // good start from the pull-off force) and the full fit starts from there: a start far from w
  // can otherwise lead the joint fit into a secondary minimum.
  // (Two adhesion energies: both of them first.)
  std::vector<int> work_index;
  for (int which : free_index) {
    if (model.names()[which].kind == ParameterKind::kWork) work_index.push_back(which);
  }
  if (fit_work_first && !work_index.empty() && work_index.size() < free_index.size()) {
    FitContext first = ctx;
    first.free_index = work_index;
    try {
      const Stage stage = run_stage(first, problem.max_iterations);
      if (stage.status == GSL_SUCCESS || stage.status == GSL_ENOPROG || stage.residuals_at_noise_floor) {
        for (int which : work_index) ctx.start.values[which] = stage.values.values[which];
        result.iterations += stage.iterations;
      }
    } catch (const NumericalError&) {
      // Keep the user's start; the full fit reports its own failure if there is one.
    }
  }
  const Stage stage = run_stage(ctx, problem.max_iterations);
  result.iterations += stage.iterations;
  result.values = stage.values;
  result.cost = stage.cost;
  if (stage.status == GSL_SUCCESS) {
    result.stop_reason = stage.info == 1 ? "small step" : "small gradient";
  } else if (stage.residuals_at_noise_floor) {
    result.stop_reason = "residuals at the model's noise level (data without noise)";
  } else if (stage.status == GSL_ENOPROG || (stage.status == GSL_EMAXITER && stage.gradient_small)) {
    // (A start at the minimum itself, as the global search gives, can leave the step test
    // unmet by the interpolant's noise: the gradient decides.)
    if (!stage.gradient_small) {
      throw NumericalError("the fit stopped making progress after " + std::to_string(result.iterations) +
                           " iterations without converging (last estimates " +
                           estimates_text(ctx, stage.x) + ")");
    }
    result.stop_reason = "no further decrease (gradient at model noise level)";
  } else if (stage.status == GSL_EMAXITER) {
    throw NumericalError("the fit did not converge in " + std::to_string(problem.max_iterations) +
                         " iterations (last estimates " + estimates_text(ctx, stage.x) + ")");
  } else {
    throw NumericalError(std::string("the fit failed: ") + gsl_strerror(stage.status) +
                         " (last estimates " + estimates_text(ctx, stage.x) + ")");
  }
  return result;
}

}  // namespace coatcontact::fit::internal
