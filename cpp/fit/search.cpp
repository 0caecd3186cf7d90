// Global search over log-parameters (search.hpp): the model is cheap once its table exists,
// so a few dozen evaluations cost little next to the table, and they remove the need for
// start values.
#include "search.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "coatcontact/errors.hpp"

namespace coatcontact::fit::internal {
namespace {

// Grid density: t needs the finest (the cost has one narrow valley in ln t); E1 costs a table
// per value and w (gridded for delta,F data only) costs full evaluations, so they get fewer.
constexpr double kPointsPerDecade = 4.0;
// Below this a/t (of the largest contact radius) the interpolant stays within its fast decades
// (they are decades of a/t: [1, 10) is the last cheap one).
constexpr double kCheapAOverT = 10.0;
// The two w at which the a,F model is evaluated to split F into A - B sqrt(w).
constexpr double kProbeWork[2] = {1e-2, 4e-2};
// Relative floor of sigma_eff (a point with sigma 0 in every variable must not get an
// infinite weight).
constexpr double kSigmaFloor = 1e-9;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Relative change of the cost along an axis below which that parameter counts as undetermined.
constexpr double kFlatCost = 1e-6;

double max_abs_force(const Measurements& data) {
  double m = 0.0;
  for (double f : data.force) m = std::max(m, std::fabs(f));
  return m;
}

}  // namespace

std::vector<double> inverse_sigma(const Measurements& data, const ModelAtData& m) {
  if (data.sigma_force.empty() && data.sigma_abscissa.empty()) return {};
  const double floor = kSigmaFloor * max_abs_force(data);
  std::vector<double> out(data.size());
  for (std::size_t i = 0; i < data.size(); ++i) {
    const double sf = data.sigma_force.empty() ? 0.0 : data.sigma_force[i];
    const double sx = data.sigma_abscissa.empty() ? 0.0 : data.sigma_abscissa[i] * m.force_x[i];
    out[i] = 1.0 / std::max(floor, std::sqrt(sf * sf + sx * sx));
  }
  return out;
}

// Cost (weighted or scaled sum of squares) of one grid point; w profiled when asked: F = A - B
// sqrt(w) at fixed a, one weighted linear fit per group of points with their own w.
struct GridCost {
  Model& model;
  const Measurements& data;
  bool profile_work;
  std::vector<std::size_t> works;  // the w parameters, one per group
  std::vector<int> group;          // each point's index into works
  double unweighted;
  int evaluations = 0;

  std::pair<double, Parameters> operator()(Parameters p) {
    const int groups = static_cast<int>(works.size());
  try {
    if (!profile_work) {
      const ModelAtData m = model.at_data(p);
      ++evaluations;
      std::vector<double> scale = inverse_sigma(data, m);
      double cost = 0.0;
      for (std::size_t i = 0; i < data.size(); ++i) {
        cost += std::pow((m.force[i] - data.force[i]) * (scale.empty() ? unweighted : scale[i]), 2);
      }
      return {cost, p};
    }
    Parameters p1 = p, p2 = p;
    for (std::size_t which : works) {
      p1.values[which] = kProbeWork[0];
      p2.values[which] = kProbeWork[1];
    }
    const ModelAtData m1 = model.at_data(p1);
    const ModelAtData m2 = model.at_data(p2);
    evaluations += 2;
    const double s1 = std::sqrt(kProbeWork[0]), s2 = std::sqrt(kProbeWork[1]);
    const std::size_t n = data.size();
    std::vector<double> A(n), B(n), Ax(n), Bx(n);
    for (std::size_t i = 0; i < n; ++i) {
      B[i] = (m1.force[i] - m2.force[i]) / (s2 - s1);
      A[i] = m1.force[i] + B[i] * s1;
      Bx[i] = (m1.force_x[i] - m2.force_x[i]) / (s2 - s1);
      Ax[i] = m1.force_x[i] + Bx[i] * s1;
    }
    // Weighted linear fit for s = sqrt(w) (one per group); the effective-variance weights
    // depend on s, so refresh them a few times.
    std::vector<double> s;
    for (std::size_t which : works) s.push_back(std::sqrt(p.values[which]));
    double cost = kInf;
    ModelAtData at_s;
    at_s.force_x.resize(n);
    for (int pass = 0; pass < 3; ++pass) {
      for (std::size_t i = 0; i < n; ++i) at_s.force_x[i] = Ax[i] - Bx[i] * s[group[i]];
      std::vector<double> scale = inverse_sigma(data, at_s);
      if (scale.empty()) scale.assign(n, unweighted);
      for (int g = 0; g < groups; ++g) {
        double num = 0.0, den = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
          if (group[i] != g) continue;
          const double u = scale[i] * scale[i];
          num += u * B[i] * (A[i] - data.force[i]);
          den += u * B[i] * B[i];
        }
        if (!(den > 0.0)) return {kInf, p};
        s[g] = std::clamp(num / den, std::sqrt(kSearchWork[0]), std::sqrt(kSearchWork[1]));
      }
      cost = 0.0;
      for (std::size_t i = 0; i < n; ++i) cost += std::pow((A[i] - B[i] * s[group[i]] - data.force[i]) * scale[i], 2);
    }
    for (int g = 0; g < groups; ++g) p.values[works[static_cast<std::size_t>(g)]] = s[g] * s[g];
    return {cost, p};
  } catch (const NumericalError&) {
    return {kInf, p};  // outside the model's range: not a candidate
  }
  }
};

// A free parameter along whose axis the cost does not move is not determined by the data (e.g. t
// when film and substrate are alike): say which, before the solve wanders off. k: the best point.
void refuse_flat_axes(const std::vector<SearchAxis>& axes, const std::vector<std::size_t>& stride,
                      const std::vector<double>& cost, std::size_t k, const std::vector<ParameterInfo>& names,
                      std::size_t layers) {
  const std::size_t dims = axes.size();
  const auto coordinate = [&](std::size_t q, std::size_t d) { return (q / stride[d]) % axes[d].values.size(); };
  const auto flat = [&](std::size_t d) {
    double lo = kInf, hi = 0.0;
    std::size_t finite = 0;
    const std::size_t base = k - coordinate(k, d) * stride[d];
    for (std::size_t j = 0; j < axes[d].values.size(); ++j) {
      const double c = cost[base + j * stride[d]];
      if (!std::isfinite(c)) continue;  // not evaluated (or not evaluable)
      ++finite;
      lo = std::min(lo, c);
      hi = std::max(hi, c);
    }
    return finite > 1 && hi - lo <= kFlatCost * hi;
  };
  // Thicknesses first, then moduli (w is not checked: its axis exists only for delta,F data).
  for (const ParameterKind kind : {ParameterKind::kThickness, ParameterKind::kModulus}) {
    for (std::size_t d = 0; d < dims; ++d) {
      const ParameterInfo& info = names[axes[d].which];
      if (info.kind != kind || axes[d].values.size() < 2 || !flat(d)) continue;
      if (kind == ParameterKind::kModulus) {
        throw NumericalError("the data do not determine " + info.name + ": the fit does not change over " +
                             info.name + " within a factor " +
                             std::to_string(static_cast<int>(kSearchModulusFactor)) + " of the given value; fix it");
      }
      throw NumericalError("the data do not determine " + info.name + ": the fit does not change for " + info.name +
                           " from " + std::to_string(axes[d].values.front()) + " to " +
                           std::to_string(axes[d].values.back()) + " m; fix it" +
                           (layers == 1 ? " with --thickness" : " (leave it out of --free)"));
    }
  }
}

SearchResult global_search(Model& model, const std::vector<int>& free_index, const Parameters& hint) {
  const Measurements& data = model.data();
  const bool radius_data = data.kind == DataKind::kRadiusForce;
  const auto is_free = [&](std::size_t which) {
    return std::find(free_index.begin(), free_index.end(), static_cast<int>(which)) != free_index.end();
  };
  const double unweighted = 1.0 / max_abs_force(data);
  const std::vector<ParameterInfo>& names = model.names();
  const ForceModel& force_model = model.force_model();
  const std::size_t layers = hint.layers;

  // Range of contact radii: measured (a,F), or sqrt(R delta) of Hertz at the largest |delta|.
  double a_lo, a_hi;
  if (radius_data) {
    a_lo = *std::min_element(data.abscissa.begin(), data.abscissa.end());
    a_hi = *std::max_element(data.abscissa.begin(), data.abscissa.end());
  } else {
    double d = 0.0;
    for (double x : data.abscissa) d = std::max(d, std::fabs(x));
    a_hi = force_model.adhesionless_radius(d);
    a_lo = 0.1 * a_hi;
  }

  // One axis per free parameter, the slowest first: the moduli and the layer thicknesses
  // (each value builds its own table), then the one film's t, then w.
  std::vector<SearchAxis> axes;
  for (std::size_t i = 0; i < layers; ++i) {
    const std::size_t which = modulus_index(i, layers);
    if (!is_free(which)) continue;
    const double e = hint.values[which];
    axes.push_back({which, log_axis(e / kSearchModulusFactor, e * kSearchModulusFactor, kCoarsePointsPerDecade)});
  }
  if (layers > 1) {
    for (std::size_t i = 0; i < layers; ++i) {
      const std::size_t which = thickness_index(i);
      if (!is_free(which)) continue;
      const double h = hint.values[which];
      axes.push_back({which, log_axis(h / kSearchThicknessFactor, h * kSearchThicknessFactor, kCoarsePointsPerDecade)});
    }
  } else if (is_free(kThickness)) {
    axes.push_back({static_cast<std::size_t>(kThickness),
                    log_axis(a_hi / kSearchAOverT[1], a_lo / kSearchAOverT[0], kPointsPerDecade)});
  }
  // (Where F is not linear in sqrt(w) at fixed a, as in the Maugis-Dugdale zone, w gets an axis.)
  const bool profile_work = is_free(kWork) && radius_data && force_model.work_separates();
  // One adhesion energy per group of points (w_load, w_unload: each branch's points depend on
  // their own only).
  const std::vector<std::size_t> works = force_model.work_parameters(hint);
  if (is_free(kWork) && !profile_work) {
    // Around the load-controlled JKR estimate when the data are tensile somewhere.
    const double estimate = force_model.work_estimate(data);
    const std::vector<double> w_axis = estimate > 0.0 ? log_axis(estimate / 10.0, estimate * 10.0, kCoarsePointsPerDecade)
                                                      : log_axis(1e-3, 1.0, kCoarsePointsPerDecade);
    for (std::size_t which : works) axes.push_back({which, w_axis});
  }
  // The model's own parameters (k of z,F data, Maugis-Dugdale's lambda), around their hints.
  force_model.add_search_axes(hint, free_index, axes);
  // The group of each point for the profiled w: the index of its w in `works`.
  std::vector<int> group(data.size(), 0);
  {
    const std::vector<std::size_t> of_point = force_model.work_parameter_of_points(hint, data);
    for (std::size_t i = 0; i < data.size(); ++i) {
      group[i] = static_cast<int>(std::find(works.begin(), works.end(), of_point[i]) - works.begin());
    }
  }

  SearchResult result;
  GridCost evaluate{model, data, profile_work, works, group, unweighted};
  // The grid: index k = mixed radix over the axes, the last one fastest.
  const std::size_t dims = axes.size();
  std::vector<std::size_t> stride(dims, 1);
  std::size_t total = 1;
  for (std::size_t d = dims; d-- > 0;) {
    stride[d] = total;
    total *= axes[d].values.size();
  }
  const auto coordinate = [&](std::size_t k, std::size_t d) { return (k / stride[d]) % axes[d].values.size(); };
  const auto point_at = [&](std::size_t k) {
    Parameters p = hint;
    for (std::size_t d = 0; d < dims; ++d) p.values[axes[d].which] = axes[d].values[coordinate(k, d)];
    return p;
  };
  const auto is_thickness = [&](std::size_t d) { return names[axes[d].which].kind == ParameterKind::kThickness; };
  // Thin coatings (a/T above kCheapAOverT) need the interpolant's slow decade a/t 10-100: they
  // are searched only when the best of the thicker ones lies at the thin edge.
  const auto thin = [&](std::size_t k) { return a_hi / point_at(k).total_thickness() >= kCheapAOverT; };
  std::vector<double> cost(total, kInf);
  std::vector<Parameters> point(total);
  const auto fill = [&](bool thin_ones) {
    for (std::size_t k = 0; k < total; ++k) {
      if (thin(k) != thin_ones) continue;
      const auto [c, p] = evaluate(point_at(k));
      cost[k] = c;
      point[k] = p;
    }
  };
  fill(false);
  {
    const std::size_t best = static_cast<std::size_t>(std::min_element(cost.begin(), cost.end()) - cost.begin());
    bool at_thin_edge = false;
    for (std::size_t d = 0; d < dims; ++d) {
      if (!is_thickness(d) || axes[d].values.size() < 2) continue;
      const std::size_t c = coordinate(best, d);
      if (c == 0 || thin(best - stride[d])) at_thin_edge = true;
    }
    if (!std::isfinite(cost[best]) || at_thin_edge) fill(true);
  }
  // Local minima: no neighbour (one step along one axis) lower.
  std::vector<std::size_t> minima;
  for (std::size_t k = 0; k < total; ++k) {
    if (!std::isfinite(cost[k])) continue;
    bool lowest = true;
    for (std::size_t d = 0; d < dims && lowest; ++d) {
      const std::size_t c = coordinate(k, d);
      if (c > 0 && cost[k - stride[d]] < cost[k]) lowest = false;
      if (c + 1 < axes[d].values.size() && cost[k + stride[d]] < cost[k]) lowest = false;
    }
    if (lowest) minima.push_back(k);
  }
  if (minima.empty()) {
    throw NumericalError("the global search found no parameters at which the model can be evaluated for these data");
  }
  std::sort(minima.begin(), minima.end(), [&](std::size_t a, std::size_t b) { return cost[a] < cost[b]; });
  refuse_flat_axes(axes, stride, cost, minima[0], names, layers);
  result.best = point[minima[0]];
  result.best_cost = cost[minima[0]];
  if (minima.size() > 1) {
    result.has_second = true;
    result.second = point[minima[1]];
    result.second_cost = cost[minima[1]];
  }
  // The user's values are a hint: a better start than the grid's best replaces it.
  const auto [hint_cost, hint_point] = evaluate(hint);
  if (hint_cost < result.best_cost) {
    result.best = hint_point;
    result.best_cost = hint_cost;
  }
  result.evaluations = evaluate.evaluations;
  return result;
}

}  // namespace coatcontact::fit::internal
