// The C interface (cpp/capi/include/coatcontact/coatcontact.h) over the C++ floors. Every entry
// point runs inside guarded(): exceptions become status codes, results are computed in full
// before anything is written to the caller's memory.
#include "coatcontact/coatcontact.h"
#include "capi_guard.hpp"
#include "capi_handles.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/crack_kinetics.hpp"
#include "coatcontact/data_file.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/fit.hpp"
#include "coatcontact/indenter_shape.hpp"
#include "coatcontact/kinetics_fit.hpp"
#include "coatcontact/maugis_dugdale.hpp"
#include "coatcontact/measured_curve.hpp"
#include "coatcontact/progress.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/shape_contact.hpp"
#include "coatcontact/shape_solver.hpp"
#include "coatcontact/stack.hpp"

using coatcontact::InputError;


// Handles share ownership of what they reference (the C++ objects keep plain references),
// so a binding's garbage collector may destroy them in any order. Members are declared in
// dependency order: the referencing object is destroyed first.
struct cc_reduced_solver {
  std::shared_ptr<const coatcontact::ReducedSolver> solver;
};

struct cc_adhesive_model {
  std::shared_ptr<const coatcontact::ReducedSolver> solver;
  std::shared_ptr<const coatcontact::AdhesiveModel> model;
  double tolerance = 0.0;
  // cc_pulloff_prepare: the pull-off sweep's model and the etas it serves (THEORY.md section 5).
  std::shared_ptr<const coatcontact::AdhesiveModel> sweep;
  double sweep_min = 0.0, sweep_max = 0.0;
};

struct cc_contact {
  std::shared_ptr<const coatcontact::ReducedSolver> solver;
  std::shared_ptr<const coatcontact::AdhesiveModel> model;
  coatcontact::Contact contact;
};

struct cc_md_model {
  std::shared_ptr<const coatcontact::MaugisDugdaleModel> model;
};

struct cc_shape_contact {
  std::shared_ptr<const coatcontact::ShapeSolver> solver;
  std::shared_ptr<const coatcontact::IndenterShape> shape;
  double sphere_radius = 0.0;
  std::unique_ptr<coatcontact::ShapeContact> contact;
};

struct cc_kinetics {
  coatcontact::KineticsResultSI run;
};

namespace {

thread_local std::string last_error;

template <typename Body>
int guarded(Body&& body) {
  try {
    last_error.clear();
    body();
    return CC_OK;
  } catch (const coatcontact::InputError& e) {
    last_error = e.what();
    return CC_INPUT_ERROR;
  } catch (const coatcontact::NumericalError& e) {
    last_error = e.what();
    return CC_NUMERICAL_ERROR;
  } catch (const coatcontact::Interrupted& e) {
    last_error = e.what();
    return CC_INTERRUPTED;
  } catch (const std::bad_alloc&) {
    last_error = "out of memory";
    return CC_INTERNAL_ERROR;
  } catch (const std::exception& e) {
    last_error = e.what();
    return CC_INTERNAL_ERROR;
  } catch (...) {
    last_error = "unknown failure";
    return CC_INTERNAL_ERROR;
  }
}

}  // namespace

int coatcontact::capi::guard(const std::function<void()>& body) { return guarded(body); }

namespace {

void require(const void* pointer, const char* function, const char* argument) {
  if (pointer == nullptr) {
    throw InputError(std::string(function) + ": " + argument + " is NULL");
  }
}

std::size_t count_of(int n, const char* function) {
  if (n < 0) throw InputError(std::string(function) + ": n = " + std::to_string(n) + " is negative");
  return static_cast<std::size_t>(n);
}

coatcontact::Material material(double e, double nu) {
  coatcontact::Material m;
  m.youngs_modulus = e;
  m.poisson_ratio = nu;
  return m;
}

coatcontact::Substrate rigid_base() {
  coatcontact::Substrate s;
  s.rigid = true;
  return s;
}

// The Stack constructor holds the rules (layer count, constants, indenter): the setters
// apply them to a trial stack so that they live in one place (THEORY.md section 12 lifts
// the one-layer rule there).
coatcontact::Stack build(const cc_stack& s) {
  if (s.layers.empty()) throw InputError("stack: no layer; add one with cc_stack_add_layer");
  if (!s.has_substrate) {
    throw InputError("stack: no substrate; set one with cc_stack_set_substrate or cc_stack_set_rigid_substrate");
  }
  return coatcontact::Stack(s.layers, s.substrate, s.indenter);
}

double tolerance_or_default(double tolerance) {
  return tolerance == 0.0 ? coatcontact::kDefaultTolerance : tolerance;
}

void write_row(const coatcontact::ReducedVariables& v, double* out) {
  const double row[CC_REDUCED_COLUMNS] = {v.a_over_t, v.pi_s,  v.delta_s, v.pi_c,
                                          v.delta_c,  v.e_eq, v.gamma1,  v.error_estimate};
  for (int k = 0; k < CC_REDUCED_COLUMNS; ++k) out[k] = row[k];
}

// Warnings of a pull-off as CC_PULLOFF_* bits. AdhesiveModel::pulloff adds at most one
// warning per control plus one for a truncated scan, so any surplus warning is that one.
int pulloff_flags(const coatcontact::Pulloff& p) {
  int flags = 0;
  std::size_t per_control = 0;
  const auto add = [&](const coatcontact::PulloffPoint& point, int several, int none) {
    if (!point.interior) {
      flags |= none;
      ++per_control;
    } else if (point.local_minima > 1) {
      flags |= several;
      ++per_control;
    }
  };
  add(p.load_control, CC_PULLOFF_LOAD_SEVERAL_MINIMA, CC_PULLOFF_LOAD_NO_MINIMUM);
  add(p.displacement_control, CC_PULLOFF_DISP_SEVERAL_MINIMA, CC_PULLOFF_DISP_NO_MINIMUM);
  if (p.warnings.size() > per_control) flags |= CC_PULLOFF_SCAN_TRUNCATED;
  return flags;
}

// n contact radii [m] -> rows a, delta, F of `contact`.
std::vector<double> contact_rows(const coatcontact::Contact& contact, const std::vector<double>& a) {
  std::vector<double> rows;
  rows.reserve(a.size() * CC_CONTACT_COLUMNS);
  for (double radius : a) {
    rows.push_back(radius);
    rows.push_back(contact.penetration(radius));
    rows.push_back(contact.force(radius));
  }
  return rows;
}

void copy_out(const std::vector<double>& values, double* out) {
  for (std::size_t k = 0; k < values.size(); ++k) out[k] = values[k];
}

// The reasons of the last _each call in this thread (cc_point_reasons).
thread_local std::string point_reasons;

// Status and reasons of an _each call: every point failed is the call's failure (nothing is
// written); else the statuses and the reasons, one line per point.
bool deliver_statuses(const std::vector<coatcontact::PointStatus>& status, int* out_status) {
  if (!status.empty() && coatcontact::failed_points(status) == status.size()) {
    // One point: its own message, as the strict call gives it.
    if (status.size() == 1) throw coatcontact::NumericalError(status.front().reason);
    throw coatcontact::NumericalError("every point of " + std::to_string(status.size()) +
                                      " failed; the first: " + status.front().reason);
  }
  std::string text;
  for (std::size_t i = 0; i < status.size(); ++i) {
    out_status[i] = status[i].delivered ? CC_OK : CC_NUMERICAL_ERROR;
    std::string reason = status[i].reason;
    for (char& c : reason) {
      if (c == '\n') c = ' ';
    }
    text += reason + "\n";
  }
  point_reasons = std::move(text);
  return true;
}

}  // namespace

namespace {

template <typename Make>
int make_shape(const char* function, cc_shape** shape, Make&& make) {
  return guarded([&] {
    require(shape, function, "shape");
    *shape = new cc_shape{make()};
  });
}

}  // namespace

extern "C" {

const char* cc_last_error_message(void) { return last_error.c_str(); }

void cc_set_progress_hook(cc_progress_hook hook, void* user) {
  if (hook == nullptr) {
    coatcontact::exchange_progress_hook({});
    return;
  }
  coatcontact::exchange_progress_hook([hook, user](std::size_t done, std::size_t total) {
    return hook(user, static_cast<long>(done), static_cast<long>(total)) == 0;
  });
}

// ---- stack ------------------------------------------------------------------------------

int cc_stack_create(cc_stack** stack) {
  return guarded([&] {
    require(stack, "cc_stack_create", "stack");
    *stack = new cc_stack();
  });
}

void cc_stack_destroy(cc_stack* stack) { delete stack; }

int cc_stack_add_layer(cc_stack* stack, double thickness, double youngs_modulus, double poisson_ratio,
                       int slip_below) {
  return guarded([&] {
    require(stack, "cc_stack_add_layer", "stack");
    // THEORY.md section 12: layers top first, slip_below != 0 a frictionless interface below.
    std::vector<coatcontact::Layer> layers = stack->layers;
    layers.push_back(coatcontact::Layer{thickness, material(youngs_modulus, poisson_ratio),
                                        slip_below != 0});
    coatcontact::Stack(layers, rigid_base(), stack->indenter);  // the library's checks
    stack->layers = std::move(layers);
  });
}

int cc_stack_set_substrate(cc_stack* stack, double youngs_modulus, double poisson_ratio) {
  return guarded([&] {
    require(stack, "cc_stack_set_substrate", "stack");
    coatcontact::Substrate substrate;
    substrate.material = material(youngs_modulus, poisson_ratio);
    coatcontact::validate(substrate);
    stack->substrate = substrate;
    stack->has_substrate = true;
  });
}

int cc_stack_set_rigid_substrate(cc_stack* stack) {
  return guarded([&] {
    require(stack, "cc_stack_set_rigid_substrate", "stack");
    stack->substrate = rigid_base();
    stack->has_substrate = true;
  });
}

int cc_stack_set_indenter(cc_stack* stack, double youngs_modulus, double poisson_ratio) {
  return guarded([&] {
    require(stack, "cc_stack_set_indenter", "stack");
    coatcontact::Indenter indenter;
    indenter.rigid = false;
    indenter.material = material(youngs_modulus, poisson_ratio);
    coatcontact::validate(indenter.material, "indenter");
    // A placeholder layer on a rigid base: only the indenter rule can fail.
    coatcontact::Stack({coatcontact::Layer{}}, rigid_base(), indenter);
    stack->indenter = indenter;
  });
}

int cc_stack_set_rigid_indenter(cc_stack* stack) {
  return guarded([&] {
    require(stack, "cc_stack_set_rigid_indenter", "stack");
    stack->indenter = coatcontact::Indenter{};
  });
}

int cc_stack_reference_modulus(const cc_stack* stack, double* reference_modulus) {
  return guarded([&] {
    require(stack, "cc_stack_reference_modulus", "stack");
    require(reference_modulus, "cc_stack_reference_modulus", "reference_modulus");
    *reference_modulus = build(*stack).reference_modulus();
  });
}

// ---- reduced solver ---------------------------------------------------------------------

int cc_reduced_solver_create(const cc_stack* stack, cc_reduced_solver** solver) {
  return guarded([&] {
    require(stack, "cc_reduced_solver_create", "stack");
    require(solver, "cc_reduced_solver_create", "solver");
    auto made = std::make_shared<const coatcontact::ReducedSolver>(build(*stack));
    *solver = new cc_reduced_solver{std::move(made)};
  });
}

void cc_reduced_solver_destroy(cc_reduced_solver* solver) { delete solver; }

int cc_reduced_solver_solve(const cc_reduced_solver* solver, double a_over_t, double tolerance,
                            double out[CC_REDUCED_COLUMNS]) {
  return guarded([&] {
    require(solver, "cc_reduced_solver_solve", "solver");
    require(out, "cc_reduced_solver_solve", "out");
    write_row(solver->solver->solve(a_over_t, tolerance_or_default(tolerance)), out);
  });
}

int cc_reduced_solver_sweep(const cc_reduced_solver* solver, int n, const double* a_over_t,
                            double tolerance, double* out) {
  return guarded([&] {
    require(solver, "cc_reduced_solver_sweep", "solver");
    const std::size_t count = count_of(n, "cc_reduced_solver_sweep");
    if (count == 0) return;
    require(a_over_t, "cc_reduced_solver_sweep", "a_over_t");
    require(out, "cc_reduced_solver_sweep", "out");
    const auto rows = solver->solver->sweep(std::vector<double>(a_over_t, a_over_t + count),
                                            tolerance_or_default(tolerance));
    for (std::size_t i = 0; i < count; ++i) write_row(rows[i], out + CC_REDUCED_COLUMNS * i);
  });
}

int cc_reduced_solver_sweep_each(const cc_reduced_solver* solver, int n, const double* a_over_t,
                                 double tolerance, double* out, int* status) {
  return guarded([&] {
    require(solver, "cc_reduced_solver_sweep_each", "solver");
    const std::size_t count = count_of(n, "cc_reduced_solver_sweep_each");
    point_reasons.clear();
    if (count == 0) return;
    require(a_over_t, "cc_reduced_solver_sweep_each", "a_over_t");
    require(out, "cc_reduced_solver_sweep_each", "out");
    require(status, "cc_reduced_solver_sweep_each", "status");
    std::vector<coatcontact::PointStatus> outcome;
    const auto rows = solver->solver->sweep(std::vector<double>(a_over_t, a_over_t + count),
                                            tolerance_or_default(tolerance), outcome);
    deliver_statuses(outcome, status);
    for (std::size_t i = 0; i < count; ++i) write_row(rows[i], out + CC_REDUCED_COLUMNS * i);
  });
}

const char* cc_point_reasons(void) { return point_reasons.c_str(); }

// ---- adhesive sphere, normalized --------------------------------------------------------

int cc_adhesive_model_create(const cc_reduced_solver* solver, double tolerance, cc_adhesive_model** model) {
  return guarded([&] {
    require(solver, "cc_adhesive_model_create", "solver");
    require(model, "cc_adhesive_model_create", "model");
    const double tol = tolerance == 0.0 ? coatcontact::kDefaultAdhesiveTolerance : tolerance;
    auto made = std::make_shared<const coatcontact::AdhesiveModel>(*solver->solver, tol);
    *model = new cc_adhesive_model{solver->solver, std::move(made), tol, nullptr};
  });
}

void cc_adhesive_model_destroy(cc_adhesive_model* model) { delete model; }

int cc_adhesive_default_range(const cc_adhesive_model* model, double range[2]) {
  return guarded([&] {
    require(model, "cc_adhesive_default_range", "model");
    require(range, "cc_adhesive_default_range", "range");
    const auto [lo, hi] = model->model->default_curve_range();
    range[0] = lo;
    range[1] = hi;
  });
}

int cc_adhesive_curve(cc_adhesive_model* model, double eta, int n, const double* a_bar, double* out) {
  return guarded([&] {
    require(model, "cc_adhesive_curve", "model");
    const std::size_t count = count_of(n, "cc_adhesive_curve");
    require(a_bar, "cc_adhesive_curve", "a_bar");
    require(out, "cc_adhesive_curve", "out");
    const auto points = model->model->curve(eta, std::vector<double>(a_bar, a_bar + count));
    std::vector<double> rows;
    rows.reserve(count * CC_CURVE_COLUMNS);
    for (const coatcontact::CurvePoint& p : points) {
      rows.insert(rows.end(), {p.a_bar, p.a_over_t, p.load, p.penetration});
    }
    copy_out(rows, out);
  });
}

int cc_adhesive_curve_each(cc_adhesive_model* model, double eta, int n, const double* a_bar, double* out,
                           int* status) {
  return guarded([&] {
    require(model, "cc_adhesive_curve_each", "model");
    const std::size_t count = count_of(n, "cc_adhesive_curve_each");
    point_reasons.clear();
    require(a_bar, "cc_adhesive_curve_each", "a_bar");
    require(out, "cc_adhesive_curve_each", "out");
    require(status, "cc_adhesive_curve_each", "status");
    std::vector<coatcontact::PointStatus> outcome;
    const auto points = model->model->curve(eta, std::vector<double>(a_bar, a_bar + count), outcome);
    deliver_statuses(outcome, status);
    std::vector<double> rows;
    rows.reserve(count * CC_CURVE_COLUMNS);
    for (const coatcontact::CurvePoint& p : points) {
      rows.insert(rows.end(), {p.a_bar, p.a_over_t, p.load, p.penetration});
    }
    copy_out(rows, out);
  });
}

int cc_pulloff_prepare(cc_adhesive_model* model, int n, const double* eta) {
  return guarded([&] {
    require(model, "cc_pulloff_prepare", "model");
    const std::size_t count = count_of(n, "cc_pulloff_prepare");
    if (count > 0) require(eta, "cc_pulloff_prepare", "eta");
    const std::vector<double> etas(eta, eta + count);
    model->sweep = coatcontact::pulloff_sweep_model(*model->solver, model->tolerance, etas);
    if (model->sweep) {
      const auto [lo, hi] = std::minmax_element(etas.begin(), etas.end());
      model->sweep_min = *lo;
      model->sweep_max = *hi;
    }
  });
}

int cc_pulloff(cc_adhesive_model* model, double eta, double out[CC_PULLOFF_COLUMNS], int* flags) {
  return guarded([&] {
    require(model, "cc_pulloff", "model");
    require(out, "cc_pulloff", "out");
    const bool swept = model->sweep && eta >= model->sweep_min && eta <= model->sweep_max;
    const coatcontact::Pulloff p = (swept ? model->sweep : model->model)->pulloff(eta);
    const auto& l = p.load_control;
    const auto& d = p.displacement_control;
    copy_out({l.load, l.a_bar, l.penetration, d.load, d.a_bar, d.penetration}, out);
    if (flags != nullptr) *flags = pulloff_flags(p);
  });
}

// ---- contact in SI units ----------------------------------------------------------------

int cc_contact_create(cc_adhesive_model* model, double sphere_radius, double thickness,
                      double work_of_adhesion, cc_contact** contact) {
  return guarded([&] {
    require(model, "cc_contact_create", "model");
    require(contact, "cc_contact_create", "contact");
    *contact = new cc_contact{model->solver, model->model,
                              coatcontact::Contact(*model->model, sphere_radius, thickness, work_of_adhesion)};
  });
}

void cc_contact_destroy(cc_contact* contact) { delete contact; }

int cc_contact_scales(const cc_contact* contact, double out[4]) {
  return guarded([&] {
    require(contact, "cc_contact_scales", "contact");
    require(out, "cc_contact_scales", "out");
    const coatcontact::Contact& c = contact->contact;
    copy_out({c.length_scale(), c.penetration_scale(), c.force_scale(), c.eta()}, out);
  });
}

int cc_contact_curve(cc_contact* contact, int n, double* out) {
  return guarded([&] {
    require(contact, "cc_contact_curve", "contact");
    const std::size_t count = count_of(n, "cc_contact_curve");
    if (count == 0) throw InputError("cc_contact_curve: n = 0; at least one point is needed");
    require(out, "cc_contact_curve", "out");
    std::vector<double> rows;
    rows.reserve(count * CC_CONTACT_COLUMNS);
    for (const auto& p : contact->contact.default_curve(count)) {
      rows.insert(rows.end(), {p.radius, p.penetration, p.force});
    }
    copy_out(rows, out);
  });
}

int cc_contact_at(cc_contact* contact, int n, const double* a, double* out) {
  return guarded([&] {
    require(contact, "cc_contact_at", "contact");
    const std::size_t count = count_of(n, "cc_contact_at");
    if (count == 0) return;
    require(a, "cc_contact_at", "a");
    require(out, "cc_contact_at", "out");
    copy_out(contact_rows(contact->contact, std::vector<double>(a, a + count)), out);
  });
}

int cc_contact_at_each(cc_contact* contact, int n, const double* a, double* out, int* status) {
  return guarded([&] {
    require(contact, "cc_contact_at_each", "contact");
    const std::size_t count = count_of(n, "cc_contact_at_each");
    point_reasons.clear();
    if (count == 0) return;
    require(a, "cc_contact_at_each", "a");
    require(out, "cc_contact_at_each", "out");
    require(status, "cc_contact_at_each", "status");
    const coatcontact::Contact& c = contact->contact;
    // The arithmetic of Contact::penetration and Contact::force, on the tolerant curve.
    std::vector<double> a_bar(count);
    for (std::size_t i = 0; i < count; ++i) {
      if (!(a[i] > 0.0) || !std::isfinite(a[i])) {
        throw InputError("contact radius = " + coatcontact::detail::full_precision(a[i]) +
                         " not allowed (need finite and > 0)");
      }
      a_bar[i] = a[i] / c.length_scale();
    }
    std::vector<coatcontact::PointStatus> outcome;
    const auto points = c.model().curve(c.eta(), a_bar, outcome);
    deliver_statuses(outcome, status);
    std::vector<double> rows;
    rows.reserve(count * CC_CONTACT_COLUMNS);
    for (std::size_t i = 0; i < count; ++i) {
      const bool ok = outcome[i].delivered;
      rows.insert(rows.end(), {a[i], ok ? c.penetration_scale() * points[i].penetration : 0.0,
                               ok ? c.force_scale() * points[i].load : 0.0});
    }
    copy_out(rows, out);
  });
}

int cc_contact_validity(const cc_contact* contact, int n, const double* rows, const char** warnings) {
  thread_local std::string text;
  return guarded([&] {
    require(contact, "cc_contact_validity", "contact");
    require(warnings, "cc_contact_validity", "warnings");
    const std::size_t count = count_of(n, "cc_contact_validity");
    if (count > 0) require(rows, "cc_contact_validity", "rows");
    std::vector<coatcontact::Contact::Point> curve(count);
    for (std::size_t i = 0; i < count; ++i) {
      curve[i] = {rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]};
    }
    text.clear();
    for (const std::string& w : contact->contact.validity_warnings(curve)) text += w + "\n";
    *warnings = text.c_str();
  });
}

int cc_contact_pulloff(cc_contact* contact, double out[CC_PULLOFF_COLUMNS], int* flags) {
  return guarded([&] {
    require(contact, "cc_contact_pulloff", "contact");
    require(out, "cc_contact_pulloff", "out");
    const coatcontact::Contact& c = contact->contact;
    const coatcontact::Pulloff& p = c.pulloff();
    const auto si = [&](const coatcontact::PulloffPoint& q) {
      return std::vector<double>{q.load * c.force_scale(), q.a_bar * c.length_scale(),
                                 q.penetration * c.penetration_scale()};
    };
    std::vector<double> rows = si(p.load_control);
    const std::vector<double> disp = si(p.displacement_control);
    rows.insert(rows.end(), disp.begin(), disp.end());
    copy_out(rows, out);
    if (flags != nullptr) *flags = pulloff_flags(p);
  });
}

// ---- fit --------------------------------------------------------------------------------

int cc_fit(const cc_stack* stack, int kind, int n, const double* x, const double* force,
           double sphere_radius, double thickness_start, double work_start, unsigned free_mask,
           cc_fit_result* out) {
  namespace fit = coatcontact::fit;
  return guarded([&] {
    require(stack, "cc_fit", "stack");
    require(x, "cc_fit", "x");
    require(force, "cc_fit", "force");
    require(out, "cc_fit", "out");
    const std::size_t count = count_of(n, "cc_fit");
    if (kind != CC_FIT_RADIUS_FORCE && kind != CC_FIT_PENETRATION_FORCE) {
      throw InputError("cc_fit: kind = " + std::to_string(kind) +
                       " is neither CC_FIT_RADIUS_FORCE (0) nor CC_FIT_PENETRATION_FORCE (1)");
    }
    const unsigned all = CC_FIT_FREE_WORK | CC_FIT_FREE_THICKNESS | CC_FIT_FREE_FILM_MODULUS;
    if (free_mask == 0u || (free_mask & ~all) != 0u) {
      throw InputError("cc_fit: free_mask = " + std::to_string(free_mask) +
                       " must be a non-empty combination of CC_FIT_FREE_WORK, CC_FIT_FREE_THICKNESS, "
                       "CC_FIT_FREE_FILM_MODULUS");
    }
    const coatcontact::Stack built = build(*stack);
    if (built.layers().size() != 1) {
      throw InputError("cc_fit: the stack has " + std::to_string(built.layers().size()) +
                       " layers; cc_fit fits one film (cc_fit_stack fits a stack)");
    }

    fit::Measurements data;
    data.kind = kind == CC_FIT_RADIUS_FORCE ? fit::DataKind::kRadiusForce : fit::DataKind::kPenetrationForce;
    data.abscissa.assign(x, x + count);
    data.force.assign(force, force + count);

    fit::Problem problem;
    problem.sphere_radius = sphere_radius;
    problem.film = built.top();
    problem.substrate = built.substrate();
    problem.thickness = thickness_start;
    problem.work = work_start;
    for (int k = 0; k < fit::kParameterCount; ++k) problem.free[k] = (free_mask >> k) & 1u;

    const fit::Result r = fit::fit(data, problem);
    cc_fit_result result{};
    for (int i = 0; i < fit::kParameterCount; ++i) {
      result.value[i] = r.value[i];
      result.standard_error[i] = r.standard_error[i];
      for (int j = 0; j < fit::kParameterCount; ++j) result.correlation[3 * i + j] = r.correlation[i][j];
    }
    result.free_mask = free_mask;
    result.points = static_cast<int>(r.points);
    result.residual_norm = r.residual_norm;
    result.residual_sigma = r.residual_sigma;
    result.r_squared = r.r_squared;
    result.iterations = r.iterations;
    result.converged = r.converged ? 1 : 0;
    result.displacement_pulloff[0] = r.displacement_pulloff_radius;
    result.displacement_pulloff[1] = r.displacement_pulloff_penetration;
    result.displacement_pulloff[2] = r.displacement_pulloff_force;
    *out = result;
  });
}

int cc_fit_stack(const cc_stack* stack, int kind, int n, const double* x, const double* force,
                 double sphere_radius, double work_start, const char* free_names, int parameter_count,
                 double* values, double* standard_errors, double* residual_sigma) {
  namespace fit = coatcontact::fit;
  return guarded([&] {
    require(stack, "cc_fit_stack", "stack");
    require(x, "cc_fit_stack", "x");
    require(force, "cc_fit_stack", "force");
    require(free_names, "cc_fit_stack", "free_names");
    require(values, "cc_fit_stack", "values");
    require(standard_errors, "cc_fit_stack", "standard_errors");
    const std::size_t count = count_of(n, "cc_fit_stack");
    if (kind != CC_FIT_RADIUS_FORCE && kind != CC_FIT_PENETRATION_FORCE) {
      throw InputError("cc_fit_stack: kind = " + std::to_string(kind) +
                       " is neither CC_FIT_RADIUS_FORCE (0) nor CC_FIT_PENETRATION_FORCE (1)");
    }
    const coatcontact::Stack built = build(*stack);
    const std::size_t layers = built.layers().size();
    const std::vector<fit::ParameterInfo> list = fit::parameter_list(layers);
    if (parameter_count != static_cast<int>(list.size())) {
      throw InputError("cc_fit_stack: parameter_count = " + std::to_string(parameter_count) + " but a " +
                       std::to_string(layers) + "-layer stack has " + std::to_string(list.size()) +
                       " parameters (w, h1..hN, E1..EN)");
    }
    fit::Problem problem;
    problem.sphere_radius = sphere_radius;
    problem.layers = built.layers();
    problem.substrate = built.substrate();
    problem.indenter = built.indenter();
    problem.work = work_start;
    std::string allowed;
    for (const auto& info : list) allowed += (allowed.empty() ? "" : ", ") + info.name;
    std::string names(free_names);
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = names.find(',', start);
      std::string name = names.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      if (layers == 1 && name == "h1") name = "t";
      std::size_t which = list.size();
      for (std::size_t k = 0; k < list.size(); ++k) {
        if (list[k].name == name) which = k;
      }
      if (which == list.size()) {
        throw InputError("cc_fit_stack: free_names: '" + name + "' is not a parameter of this " +
                         std::to_string(layers) + "-layer stack (allowed: " + allowed + ")");
      }
      problem.free_parameters.push_back(which);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    fit::Measurements data;
    data.kind = kind == CC_FIT_RADIUS_FORCE ? fit::DataKind::kRadiusForce : fit::DataKind::kPenetrationForce;
    data.abscissa.assign(x, x + count);
    data.force.assign(force, force + count);
    const fit::Result r = fit::fit(data, problem);
    std::copy(r.value.begin(), r.value.end(), values);
    std::copy(r.standard_error.begin(), r.standard_error.end(), standard_errors);
    if (residual_sigma != nullptr) *residual_sigma = r.residual_sigma;
  });
}

namespace {

namespace fit = coatcontact::fit;

bool names_work_pair(const std::string& names) {
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = names.find(',', start);
    const std::string name = names.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (name == "w_load" || name == "w_unload") return true;
    if (comma == std::string::npos) return false;
    start = comma + 1;
  }
}

std::vector<fit::ParameterInfo> request_parameters(const coatcontact::Stack& stack, const cc_fit_request& r) {
  const char* names = r.free_names != nullptr ? r.free_names : "w";
  return fit::parameter_list(stack.layers().size(), names_work_pair(names), r.kind == CC_FIT_BASE_FORCE,
                             r.model == CC_FIT_MAUGIS_DUGDALE);
}

void check_request(const cc_fit_request* r, const char* function) {
  require(r, function, "request");
  if (r->kind != CC_FIT_RADIUS_FORCE && r->kind != CC_FIT_PENETRATION_FORCE && r->kind != CC_FIT_BASE_FORCE) {
    throw InputError(std::string(function) + ": kind = " + std::to_string(r->kind) +
                     " is none of CC_FIT_RADIUS_FORCE (0), CC_FIT_PENETRATION_FORCE (1), CC_FIT_BASE_FORCE (2)");
  }
  if (r->model != CC_FIT_JKR && r->model != CC_FIT_MAUGIS_DUGDALE) {
    throw InputError(std::string(function) + ": model = " + std::to_string(r->model) +
                     " is neither CC_FIT_JKR (0) nor CC_FIT_MAUGIS_DUGDALE (1)");
  }
}

// The data and the problem of a request (the library's fit::Problem, the C request's fields).
std::pair<fit::Measurements, fit::Problem> request_problem(const coatcontact::Stack& stack, const cc_fit_request& r) {
  const std::size_t count = count_of(r.n, "cc_fit_run");
  require(r.x, "cc_fit_run", "request->x");
  require(r.force, "cc_fit_run", "request->force");
  fit::Measurements data;
  data.kind = r.kind == CC_FIT_RADIUS_FORCE ? fit::DataKind::kRadiusForce : fit::DataKind::kPenetrationForce;
  data.abscissa.assign(r.x, r.x + count);
  data.force.assign(r.force, r.force + count);
  if (r.sigma_x != nullptr) data.sigma_abscissa.assign(r.sigma_x, r.sigma_x + count);
  if (r.sigma_force != nullptr) data.sigma_force.assign(r.sigma_force, r.sigma_force + count);
  const std::vector<fit::ParameterInfo> list = request_parameters(stack, r);
  fit::Problem problem;
  problem.hysteresis = list.front().name == "w_load";
  problem.base_displacement = r.kind == CC_FIT_BASE_FORCE;
  problem.maugis_dugdale = r.model == CC_FIT_MAUGIS_DUGDALE;
  if (problem.hysteresis) {
    if (r.unloading != nullptr) {
      for (std::size_t i = 0; i < count; ++i) data.unloading.push_back(r.unloading[i] != 0);
    } else {
      data.unloading = fit::unloading_by_order(data);
    }
  }
  problem.sphere_radius = r.sphere_radius;
  if (r.shape != nullptr) problem.shape = r.shape->shape;
  if (stack.layers().size() == 1) {
    problem.film = stack.top();
    problem.thickness = stack.layers().front().thickness;
  } else {
    problem.layers = stack.layers();
  }
  problem.substrate = stack.substrate();
  problem.indenter = stack.indenter();
  problem.spring_stiffness = r.spring_stiffness;
  problem.lambda = r.lambda > 0.0 ? r.lambda : 1.0;
  problem.bootstrap = r.bootstrap;
  problem.bootstrap_seed = r.seed != 0 ? r.seed : 1;
  const std::string names = r.free_names != nullptr ? r.free_names : "w";
  std::string allowed;
  for (const auto& info : list) allowed += (allowed.empty() ? "" : ", ") + info.name;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = names.find(',', start);
    std::string name = names.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (list.size() > 1 && stack.layers().size() == 1 && name == "h1") name = "t";
    std::size_t which = list.size();
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (list[k].name == name) which = k;
    }
    if (which == list.size()) {
      throw InputError("cc_fit_run: free_names: '" + name + "' is not a parameter of this fit (allowed: " + allowed + ")");
    }
    problem.free_parameters.push_back(which);
    if (which < static_cast<std::size_t>(fit::kParameterCount)) problem.free[which] = true;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (std::find(problem.free_parameters.begin(), problem.free_parameters.end(), 0u) == problem.free_parameters.end()) {
    problem.free[fit::kWork] = false;
  }
  const double estimate = fit::start_work(data, problem);
  problem.work = r.work > 0.0 ? r.work : estimate;
  problem.unload_work = r.unload_work > 0.0 ? r.unload_work : problem.work;
  return {std::move(data), std::move(problem)};
}

void copy_triple(double a, double b, double c, double out[3]) {
  out[0] = a;
  out[1] = b;
  out[2] = c;
}

}  // namespace

int cc_fit_parameter_names(const cc_stack* stack, const cc_fit_request* request, char* names, int size, int* count) {
  return guarded([&] {
    require(stack, "cc_fit_parameter_names", "stack");
    check_request(request, "cc_fit_parameter_names");
    require(names, "cc_fit_parameter_names", "names");
    const std::vector<fit::ParameterInfo> list = request_parameters(build(*stack), *request);
    std::string text;
    for (const auto& info : list) text += (text.empty() ? "" : ",") + info.name;
    if (size < 1 || text.size() + 1 > static_cast<std::size_t>(size)) {
      throw InputError("cc_fit_parameter_names: size = " + std::to_string(size) + " holds fewer than the " +
                       std::to_string(text.size() + 1) + " bytes of the names");
    }
    std::copy(text.begin(), text.end(), names);
    names[text.size()] = '\0';
    if (count != nullptr) *count = static_cast<int>(list.size());
  });
}

int cc_fit_run(const cc_stack* stack, const cc_fit_request* request, int parameter_count, double* values,
               double* standard_errors, double* start, double* correlation, double* interval68, double* interval95,
               double* model_force, double* model_x, cc_fit_summary* summary) {
  return guarded([&] {
    require(stack, "cc_fit_run", "stack");
    check_request(request, "cc_fit_run");
    require(values, "cc_fit_run", "values");
    require(standard_errors, "cc_fit_run", "standard_errors");
    const coatcontact::Stack built = build(*stack);
    const auto [data, problem] = request_problem(built, *request);
    const std::size_t p = request_parameters(built, *request).size();
    if (parameter_count != static_cast<int>(p)) {
      throw InputError("cc_fit_run: parameter_count = " + std::to_string(parameter_count) + " but this fit has " +
                       std::to_string(p) + " parameters (cc_fit_parameter_names)");
    }
    const fit::Result r = fit::fit(data, problem);
    copy_out(r.value, values);
    copy_out(r.standard_error, standard_errors);
    if (start != nullptr) {
      // The hints and fixed values, in the order of the parameter vector.
      std::vector<double> hint{problem.work};
      const std::vector<coatcontact::Layer> layers =
          problem.layers.empty() ? std::vector<coatcontact::Layer>{{problem.thickness, problem.film}} : problem.layers;
      for (const auto& layer : layers) hint.push_back(layer.thickness);
      for (const auto& layer : layers) hint.push_back(layer.material.youngs_modulus);
      if (problem.hysteresis) hint.push_back(problem.unload_work);
      if (problem.base_displacement) hint.push_back(problem.spring_stiffness);
      if (problem.maugis_dugdale) hint.push_back(problem.lambda);
      copy_out(hint, start);
    }
    if (correlation != nullptr) {
      for (std::size_t i = 0; i < p; ++i) copy_out(r.correlation[i], correlation + i * p);
    }
    const auto intervals = [&](const std::vector<double>& low, const std::vector<double>& high, double* out) {
      if (out == nullptr) return;
      for (std::size_t i = 0; i < p; ++i) {
        out[2 * i] = low.empty() ? 0.0 : low[i];
        out[2 * i + 1] = high.empty() ? 0.0 : high[i];
      }
    };
    intervals(r.interval68_low, r.interval68_high, interval68);
    intervals(r.interval95_low, r.interval95_high, interval95);
    if (model_force != nullptr) copy_out(r.model_force, model_force);
    if (model_x != nullptr) copy_out(r.model_radius, model_x);
    if (summary != nullptr) {
      cc_fit_summary s{};
      s.parameter_count = static_cast<int>(p);
      s.points = static_cast<int>(r.points);
      s.iterations = r.iterations;
      s.weighted = r.weighted ? 1 : 0;
      s.residual_norm = r.residual_norm;
      s.residual_sigma = r.residual_sigma;
      s.r_squared = r.r_squared;
      s.chi2_per_dof = r.chi2_per_dof;
      s.has_load_pulloff = r.has_load_pulloff ? 1 : 0;
      copy_triple(r.load_pulloff_force, r.load_pulloff_radius, r.load_pulloff_penetration, s.load_pulloff);
      s.has_displacement_pulloff = r.displacement_pulloff_radius > 0.0 ? 1 : 0;
      copy_triple(r.displacement_pulloff_force, r.displacement_pulloff_radius, r.displacement_pulloff_penetration,
                  s.displacement_pulloff);
      s.has_spring_pulloff = r.has_spring_pulloff ? 1 : 0;
      copy_triple(r.spring_pulloff_force, r.spring_pulloff_radius, r.spring_pulloff_penetration, s.spring_pulloff);
      s.bootstrap_samples = r.bootstrap_samples;
      *summary = s;
    }
  });
}

// ---- measured force curves ----------------------------------------------------------------

struct cc_curve {
  coatcontact::measure::MeasuredCurve curve;
};

int cc_curve_read(const char* path, const char* columns, cc_curve** curve) {
  return guarded([&] {
    require(path, "cc_curve_read", "path");
    require(columns, "cc_curve_read", "columns");
    require(curve, "cc_curve_read", "curve");
    *curve = nullptr;
    const auto choice = coatcontact::measure::parse_curve_columns(columns, "columns");
    auto made = std::make_unique<cc_curve>();
    made->curve = coatcontact::measure::read_curve_text(coatcontact::read_file_text(path),
                                                        coatcontact::short_name(path), choice);
    *curve = made.release();
  });
}

void cc_curve_destroy(cc_curve* curve) { delete curve; }

int cc_curve_size(const cc_curve* curve, int* rows, int* kind) {
  return guarded([&] {
    require(curve, "cc_curve_size", "curve");
    if (rows != nullptr) *rows = static_cast<int>(curve->curve.force.size());
    if (kind != nullptr) {
      const auto a = curve->curve.abscissa;
      *kind = a == coatcontact::measure::Abscissa::kRadius        ? CC_FIT_RADIUS_FORCE
              : a == coatcontact::measure::Abscissa::kPenetration ? CC_FIT_PENETRATION_FORCE
                                                                  : CC_FIT_BASE_FORCE;
    }
  });
}

int cc_curve_column(const cc_curve* curve, int column, double* out) {
  return guarded([&] {
    require(curve, "cc_curve_column", "curve");
    require(out, "cc_curve_column", "out");
    const coatcontact::measure::MeasuredCurve& c = curve->curve;
    const std::vector<double>* values = nullptr;
    std::vector<double> lines;
    switch (column) {
      case CC_CURVE_X: values = &c.x; break;
      case CC_CURVE_F: values = &c.force; break;
      case CC_CURVE_SIGMA_X: values = &c.sigma_x; break;
      case CC_CURVE_SIGMA_F: values = &c.sigma_force; break;
      case CC_CURVE_BRANCH: values = &c.branch; break;
      case CC_CURVE_LINE:
        lines.assign(c.line_numbers.begin(), c.line_numbers.end());
        values = &lines;
        break;
      default: throw InputError("cc_curve_column: column = " + std::to_string(column) + " is not a cc_curve_column");
    }
    if (values->empty()) throw InputError("cc_curve_column: the file has no column " + std::to_string(column));
    copy_out(*values, out);
  });
}

int cc_curve_units(const cc_curve* curve, char* text, int size) {
  return guarded([&] {
    require(curve, "cc_curve_units", "curve");
    require(text, "cc_curve_units", "text");
    const std::string& units = curve->curve.units;
    if (size < 1 || units.size() + 1 > static_cast<std::size_t>(size)) {
      throw InputError("cc_curve_units: size = " + std::to_string(size) + " is too small");
    }
    std::copy(units.begin(), units.end(), text);
    text[units.size()] = '\0';
  });
}

// ---- spring control ---------------------------------------------------------------------

int cc_pulloff_spring(cc_adhesive_model* model, double eta, double k_bar, double out[3], int* flags) {
  return guarded([&] {
    require(model, "cc_pulloff_spring", "model");
    require(out, "cc_pulloff_spring", "out");
    const coatcontact::SpringPulloff p = model->model->pulloff_spring(eta, k_bar);
    copy_out({p.point.load, p.point.a_bar, p.point.penetration}, out);
    if (flags != nullptr) {
      int bits = 0;
      if (!p.point.interior) bits |= CC_PULLOFF_LOAD_NO_MINIMUM;
      else if (p.point.local_minima > 1) bits |= CC_PULLOFF_LOAD_SEVERAL_MINIMA;
      *flags = bits;
    }
  });
}

// ---- Maugis-Dugdale ---------------------------------------------------------------------

namespace {

// THEORY.md section 13: the reduced table of the cohesive zone (the default) or the direct
// per-radius solve (the reference, the CLI's --md-direct).
int create_md_model(const cc_stack* stack, bool direct, const char* function, cc_md_model** model) {
  return guarded([&] {
    require(stack, function, "stack");
    require(model, function, "model");
    coatcontact::MaugisDugdaleOptions options;
    options.use_table = !direct;
    *model = new cc_md_model{std::make_shared<const coatcontact::MaugisDugdaleModel>(build(*stack), options)};
  });
}

}  // namespace

int cc_md_model_create(const cc_stack* stack, cc_md_model** model) {
  return create_md_model(stack, false, "cc_md_model_create", model);
}

int cc_md_model_create_direct(const cc_stack* stack, cc_md_model** model) {
  return create_md_model(stack, true, "cc_md_model_create_direct", model);
}

void cc_md_model_destroy(cc_md_model* model) { delete model; }

int cc_md_curve(const cc_md_model* model, double eta, double lambda, int n, const double* a_bar,
                double* out) {
  return guarded([&] {
    require(model, "cc_md_curve", "model");
    const std::size_t count = count_of(n, "cc_md_curve");
    require(a_bar, "cc_md_curve", "a_bar");
    require(out, "cc_md_curve", "out");
    const auto points = model->model->curve(eta, lambda, std::vector<double>(a_bar, a_bar + count));
    std::vector<double> rows;
    rows.reserve(count * CC_MD_CURVE_COLUMNS);
    for (const coatcontact::MaugisDugdalePoint& p : points) {
      rows.insert(rows.end(), {p.a_bar, p.a_over_t, p.m, p.load, p.penetration});
    }
    copy_out(rows, out);
  });
}

namespace {

int md_pulloff(const char* function, const cc_md_model* model, double eta, double lambda, double* out,
               double* errors, int* flags, bool all_errors = false) {
  return guarded([&] {
    require(model, function, "model");
    require(out, function, "out");
    const coatcontact::MaugisDugdalePulloff p = model->model->pulloff(eta, lambda);
    const auto& l = p.load_control.point;
    const auto& d = p.displacement_control.point;
    copy_out({l.load, l.a_bar, l.penetration, l.m, d.load, d.a_bar, d.penetration, d.m}, out);
    if (errors != nullptr && all_errors) {
      copy_out({l.load_error, l.a_bar_error, l.penetration_error, l.m_error, d.load_error, d.a_bar_error,
                d.penetration_error, d.m_error},
               errors);
    } else if (errors != nullptr) {
      copy_out({l.load_error, d.penetration_error}, errors);
    }
    if (flags != nullptr) *flags = p.displacement_control.interior ? 0 : 1;
  });
}

}  // namespace

int cc_md_pulloff(const cc_md_model* model, double eta, double lambda,
                  double out[CC_MD_PULLOFF_COLUMNS], int* flags) {
  return md_pulloff("cc_md_pulloff", model, eta, lambda, out, nullptr, flags);
}

int cc_md_pulloff_errors(const cc_md_model* model, double eta, double lambda,
                         double out[CC_MD_PULLOFF_COLUMNS], double errors[CC_MD_PULLOFF_ERROR_COLUMNS],
                         int* flags) {
  return md_pulloff("cc_md_pulloff_errors", model, eta, lambda, out, errors, flags);
}

int cc_md_pulloff_all_errors(const cc_md_model* model, double eta, double lambda,
                             double out[CC_MD_PULLOFF_COLUMNS], double errors[CC_MD_PULLOFF_ALL_ERROR_COLUMNS],
                             int* flags) {
  return md_pulloff("cc_md_pulloff_all_errors", model, eta, lambda, out, errors, flags, true);
}

// ---- shapes and their SI contact --------------------------------------------------------

int cc_shape_paraboloid(double radius, cc_shape** shape) {
  const int status =
      make_shape("cc_shape_paraboloid", shape, [&] { return coatcontact::make_paraboloid(radius); });
  if (status == CC_OK) (*shape)->sphere_radius = radius;
  return status;
}
int cc_shape_cone(double beta, cc_shape** shape) {
  return make_shape("cc_shape_cone", shape, [&] { return coatcontact::make_cone(beta); });
}
int cc_shape_pyramid(double theta, cc_shape** shape) {
  return make_shape("cc_shape_pyramid", shape, [&] { return coatcontact::make_pyramid(theta); });
}
int cc_shape_flat_punch(double radius, cc_shape** shape) {
  return make_shape("cc_shape_flat_punch", shape, [&] { return coatcontact::make_flat_punch(radius); });
}
int cc_shape_power_law(double n, double radius, cc_shape** shape) {
  return make_shape("cc_shape_power_law", shape, [&] { return coatcontact::make_power_law(n, radius); });
}
int cc_shape_blunted_cone(double radius, double beta, cc_shape** shape) {
  return make_shape("cc_shape_blunted_cone", shape,
                    [&] { return coatcontact::make_blunted_cone(radius, beta); });
}
int cc_shape_profile(int n, const double* r, const double* z, cc_shape** shape) {
  return make_shape("cc_shape_profile", shape, [&] {
    const std::size_t count = count_of(n, "cc_shape_profile");
    require(r, "cc_shape_profile", "r");
    require(z, "cc_shape_profile", "z");
    return coatcontact::make_measured_profile(std::vector<double>(r, r + count),
                                              std::vector<double>(z, z + count), "cc_shape_profile");
  });
}
void cc_shape_destroy(cc_shape* shape) { delete shape; }

int cc_shape_contact_create(const cc_stack* stack, const cc_shape* shape, double thickness,
                            double work_of_adhesion, double tolerance, cc_shape_contact** contact) {
  return guarded([&] {
    require(stack, "cc_shape_contact_create", "stack");
    require(shape, "cc_shape_contact_create", "shape");
    require(contact, "cc_shape_contact_create", "contact");
    auto handle = std::make_unique<cc_shape_contact>();
    handle->solver = std::make_shared<const coatcontact::ShapeSolver>(build(*stack));
    handle->shape = shape->shape;
    handle->sphere_radius = shape->sphere_radius;
    handle->contact = std::make_unique<coatcontact::ShapeContact>(
        *handle->solver, handle->shape, thickness, work_of_adhesion, tolerance_or_default(tolerance));
    *contact = handle.release();
  });
}

void cc_shape_contact_destroy(cc_shape_contact* contact) { delete contact; }

int cc_shape_contact_default_range(const cc_shape_contact* contact, double range[2]) {
  return guarded([&] {
    require(contact, "cc_shape_contact_default_range", "contact");
    require(range, "cc_shape_contact_default_range", "range");
    const auto [lo, hi] = contact->contact->default_range();
    range[0] = lo;
    range[1] = hi;
  });
}

int cc_shape_contact_validity(const cc_shape_contact* contact, int n, const double* rows, const char** warnings) {
  thread_local std::string text;
  return guarded([&] {
    require(contact, "cc_shape_contact_validity", "contact");
    require(warnings, "cc_shape_contact_validity", "warnings");
    const std::size_t count = count_of(n, "cc_shape_contact_validity");
    if (count > 0) require(rows, "cc_shape_contact_validity", "rows");
    std::vector<coatcontact::ShapePoint> curve(count);
    for (std::size_t i = 0; i < count; ++i) {
      curve[i].radius = rows[CC_SHAPE_CURVE_COLUMNS * i];
      curve[i].penetration = rows[CC_SHAPE_CURVE_COLUMNS * i + 1];
      curve[i].force = rows[CC_SHAPE_CURVE_COLUMNS * i + 2];
    }
    text.clear();
    for (const std::string& w : contact->contact->validity_warnings(curve, contact->sphere_radius)) text += w + "\n";
    *warnings = text.c_str();
  });
}

int cc_shape_contact_curve(const cc_shape_contact* contact, int n, const double* a, double* out) {
  return guarded([&] {
    require(contact, "cc_shape_contact_curve", "contact");
    const std::size_t count = count_of(n, "cc_shape_contact_curve");
    require(a, "cc_shape_contact_curve", "a");
    require(out, "cc_shape_contact_curve", "out");
    const auto points = contact->contact->curve(std::vector<double>(a, a + count));
    std::vector<double> rows;
    rows.reserve(count * CC_SHAPE_CURVE_COLUMNS);
    for (const coatcontact::ShapePoint& p : points) {
      rows.insert(rows.end(), {p.radius, p.penetration, p.force, p.penetration_h, p.force_h});
    }
    copy_out(rows, out);
  });
}

int cc_shape_contact_curve_each(const cc_shape_contact* contact, int n, const double* a, double* out, int* status) {
  return guarded([&] {
    require(contact, "cc_shape_contact_curve_each", "contact");
    const std::size_t count = count_of(n, "cc_shape_contact_curve_each");
    point_reasons.clear();
    require(a, "cc_shape_contact_curve_each", "a");
    require(out, "cc_shape_contact_curve_each", "out");
    require(status, "cc_shape_contact_curve_each", "status");
    std::vector<coatcontact::PointStatus> outcome;
    const auto points = contact->contact->curve(std::vector<double>(a, a + count), outcome);
    deliver_statuses(outcome, status);
    std::vector<double> rows;
    rows.reserve(count * CC_SHAPE_CURVE_COLUMNS);
    for (const coatcontact::ShapePoint& p : points) {
      rows.insert(rows.end(), {p.radius, p.penetration, p.force, p.penetration_h, p.force_h});
    }
    copy_out(rows, out);
  });
}

int cc_shape_contact_pulloff(const cc_shape_contact* contact, double spring_stiffness,
                             double out[CC_SHAPE_PULLOFF_COLUMNS]) {
  return guarded([&] {
    require(contact, "cc_shape_contact_pulloff", "contact");
    require(out, "cc_shape_contact_pulloff", "out");
    const coatcontact::ShapePulloff p = contact->contact->pulloff(spring_stiffness);
    copy_out({p.load.force, p.load.radius, p.load.penetration, p.displacement.force, p.displacement.radius,
              p.displacement.penetration, p.spring.force, p.spring.radius, p.spring.penetration},
             out);
  });
}

}  // extern "C"

// ---- crack kinetics (THEORY.md section 14) ----

namespace {

// The SI protocol of segment_count C segments (`name`: the array, for the messages).
std::vector<coatcontact::KineticsSegmentSI> kinetics_protocol(int segment_count, const cc_kinetics_segment* segments,
                                                              const char* function, const char* name) {
  using coatcontact::DriveSegment;
  std::vector<coatcontact::KineticsSegmentSI> protocol;
  const std::size_t count = count_of(segment_count, function);
  if (count > 0) require(segments, function, name);
  for (std::size_t i = 0; i < count; ++i) {
    const cc_kinetics_segment& in = segments[i];
    coatcontact::KineticsSegmentSI out;
    switch (in.kind) {
      case CC_KINETICS_APPROACH: out.kind = DriveSegment::Kind::kApproach; out.has_target = true; break;
      case CC_KINETICS_DWELL: out.kind = DriveSegment::Kind::kDwell; break;
      case CC_KINETICS_RETRACT: out.kind = DriveSegment::Kind::kRetract; out.has_target = in.has_target != 0; break;
      default:
        throw InputError(std::string(function) + ": segment " + std::to_string(i + 1) + ": kind " +
                         std::to_string(in.kind) + " not allowed (CC_KINETICS_APPROACH, _DWELL or _RETRACT)");
    }
    out.speed = in.speed;
    out.duration = in.duration;
    out.target_force = in.target_force;
    protocol.push_back(out);
  }
  return protocol;
}

// The stack and the SI setup of a kinetics call; the coating thickness is the stack's total.
coatcontact::KineticsSetupSI kinetics_setup(const coatcontact::Stack& stack, const cc_kinetics_setup& c,
                                            const char* function) {
  coatcontact::KineticsSetupSI setup;
  if (c.tip != CC_KINETICS_SPHERE && c.tip != CC_KINETICS_CONE) {
    throw InputError(std::string(function) + ": setup->tip = " + std::to_string(c.tip) +
                     " not allowed (CC_KINETICS_SPHERE or CC_KINETICS_CONE)");
  }
  setup.tip = c.tip == CC_KINETICS_CONE ? coatcontact::KineticsTip::kCone : coatcontact::KineticsTip::kSphere;
  setup.radius = c.radius;
  setup.half_angle = c.half_angle;
  setup.thickness = stack.total_thickness();
  setup.work = c.work;
  setup.v_star = c.v_star;
  setup.n = c.n;
  setup.v_star_adv = c.v_star_adv;
  setup.n_adv = c.n_adv;
  setup.spring = c.spring;
  setup.protocol = kinetics_protocol(c.segment_count, c.segments, function, "setup->segments");
  return setup;
}

struct KineticsRuns {
  std::vector<coatcontact::KineticsResultSI> runs;
  double drive_rate = 0.0;  // reduced drive rate per SI speed
};

KineticsRuns kinetics_runs(const cc_stack* stack, const cc_kinetics_setup* setup, const std::vector<double>& speeds,
                           const char* function) {
  require(stack, function, "stack");
  require(setup, function, "setup");
  const coatcontact::Stack built = build(*stack);
  const coatcontact::KineticsSetupSI si = kinetics_setup(built, *setup, function);
  const coatcontact::ReducedSolver solver(built);
  const coatcontact::AdhesiveModel model(solver, tolerance_or_default(setup->tolerance));
  KineticsRuns out;
  out.drive_rate = coatcontact::kinetics_scales(model, si).drive_rate;
  out.runs = coatcontact::simulate_kinetics_si(model, si, speeds, speeds.empty());
  return out;
}

}  // namespace

extern "C" {

int cc_kinetics_run(const cc_stack* stack, const cc_kinetics_setup* setup, cc_kinetics** run) {
  return guarded([&] {
    require(run, "cc_kinetics_run", "run");
    auto out = std::make_unique<cc_kinetics>();
    out->run = kinetics_runs(stack, setup, {}, "cc_kinetics_run").runs.front();
    *run = out.release();
  });
}

void cc_kinetics_destroy(cc_kinetics* run) { delete run; }

int cc_kinetics_size(const cc_kinetics* run, int* rows) {
  return guarded([&] {
    require(run, "cc_kinetics_size", "run");
    require(rows, "cc_kinetics_size", "rows");
    *rows = static_cast<int>(run->run.t.size());
  });
}

int cc_kinetics_states(const cc_kinetics* run, int rows, double* out) {
  return guarded([&] {
    require(run, "cc_kinetics_states", "run");
    require(out, "cc_kinetics_states", "out");
    const coatcontact::KineticsResultSI& r = run->run;
    if (rows < 0 || static_cast<std::size_t>(rows) != r.t.size()) {
      throw InputError("cc_kinetics_states: rows = " + std::to_string(rows) + " but the run has " +
                       std::to_string(r.t.size()) + " states (cc_kinetics_size)");
    }
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      const double row[CC_KINETICS_COLUMNS] = {r.t[i], r.z[i], r.delta[i], r.a[i], r.force[i], r.g[i]};
      std::copy(row, row + CC_KINETICS_COLUMNS, out + i * CC_KINETICS_COLUMNS);
    }
  });
}

int cc_kinetics_events(const cc_kinetics* run, double out[CC_KINETICS_EVENT_COLUMNS]) {
  return guarded([&] {
    require(run, "cc_kinetics_events", "run");
    require(out, "cc_kinetics_events", "out");
    const coatcontact::KineticsResultSI& r = run->run;
    const double row[CC_KINETICS_EVENT_COLUMNS] = {r.pulloff.force, r.pulloff.time, r.pulloff.radius,
                                                   r.loss.force,    r.loss.time,    r.loss.radius};
    std::copy(row, row + CC_KINETICS_EVENT_COLUMNS, out);
  });
}

int cc_kinetics_sweep(const cc_stack* stack, const cc_kinetics_setup* setup, int n, const double* retract_speeds,
                      double* out) {
  return guarded([&] {
    const std::size_t count = count_of(n, "cc_kinetics_sweep");
    if (count == 0) throw InputError("cc_kinetics_sweep: n = 0 (need at least one retract speed)");
    require(retract_speeds, "cc_kinetics_sweep", "retract_speeds");
    require(out, "cc_kinetics_sweep", "out");
    const std::vector<double> speeds(retract_speeds, retract_speeds + count);
    const KineticsRuns sweep = kinetics_runs(stack, setup, speeds, "cc_kinetics_sweep");
    std::vector<double> rows;
    for (const coatcontact::KineticsResultSI& r : sweep.runs) {
      const double row[CC_KINETICS_SWEEP_COLUMNS] = {r.retract_speed,
                                                     r.pulloff.force,
                                                     r.pulloff.time,
                                                     r.pulloff.radius,
                                                     r.loss.force,
                                                     r.loss.time,
                                                     r.retract_speed * sweep.drive_rate,
                                                     r.reduced.pulloff.load};
      rows.insert(rows.end(), row, row + CC_KINETICS_SWEEP_COLUMNS);
    }
    std::copy(rows.begin(), rows.end(), out);
  });
}

int cc_kinetics_scales(const cc_stack* stack, const cc_kinetics_setup* setup, double out[CC_KINETICS_SCALE_COLUMNS]) {
  return guarded([&] {
    require(stack, "cc_kinetics_scales", "stack");
    require(setup, "cc_kinetics_scales", "setup");
    require(out, "cc_kinetics_scales", "out");
    const coatcontact::Stack built = build(*stack);
    const coatcontact::KineticsSetupSI si = kinetics_setup(built, *setup, "cc_kinetics_scales");
    const coatcontact::ReducedSolver solver(built);
    const coatcontact::AdhesiveModel model(solver, tolerance_or_default(setup->tolerance));
    const coatcontact::KineticsScales s = coatcontact::kinetics_scales(model, si);
    const double row[CC_KINETICS_SCALE_COLUMNS] = {s.length, s.penetration, s.force, s.time,
                                                   s.eta,    s.k_bar,       s.drive_rate};
    std::copy(row, row + CC_KINETICS_SCALE_COLUMNS, out);
  });
}

int cc_kinetics_energy(const cc_kinetics* run, double out[CC_KINETICS_ENERGY_COLUMNS]) {
  return guarded([&] {
    require(run, "cc_kinetics_energy", "run");
    require(out, "cc_kinetics_energy", "out");
    const coatcontact::KineticsResult& r = run->run.reduced;
    const double row[CC_KINETICS_ENERGY_COLUMNS] = {r.work, r.dissipation, static_cast<double>(r.steps)};
    std::copy(row, row + CC_KINETICS_ENERGY_COLUMNS, out);
  });
}

int cc_kinetics_fit(const cc_stack* stack, const cc_kinetics_fit_request* request, double* values,
                    double* standard_errors, double* correlation, double* model_force, double* residual,
                    cc_kinetics_fit_summary* summary) {
  return guarded([&] {
    const char* function = "cc_kinetics_fit";
    require(stack, function, "stack");
    require(request, function, "request");
    require(values, function, "values");
    require(standard_errors, function, "standard_errors");
    require(summary, function, "summary");
    const coatcontact::Stack built = build(*stack);
    namespace fit = coatcontact::fit;
    fit::KineticsFitProblem problem;
    problem.radius = request->radius;
    problem.thickness = built.total_thickness();
    problem.work = request->work;
    problem.v_star = request->v_star;
    problem.n = request->n;
    problem.v_star_adv = request->v_star_adv;
    problem.n_adv = request->n_adv;
    problem.solver_tolerance = tolerance_or_default(request->tolerance);
    for (int j = 0; j < CC_KINETICS_FIT_PARAMETERS; ++j) problem.free[static_cast<std::size_t>(j)] = request->free[j] != 0;
    const std::size_t curve_count = count_of(request->curve_count, function);
    if (curve_count > 0) require(request->curves, function, "request->curves");
    std::vector<fit::KineticsCurve> curves;
    for (std::size_t c = 0; c < curve_count; ++c) {
      const cc_kinetics_curve& in = request->curves[c];
      fit::KineticsCurve curve;
      curve.protocol = kinetics_protocol(in.segment_count, in.segments, function, "curve segments");
      curve.spring = in.spring;
      const std::size_t n = count_of(in.n, function);
      if (n > 0) {
        require(in.time, function, "curve time");
        require(in.force, function, "curve force");
      }
      curve.time.assign(in.time, in.time + n);
      curve.force.assign(in.force, in.force + n);
      if (in.sigma_force != nullptr) curve.sigma_force.assign(in.sigma_force, in.sigma_force + n);
      curves.push_back(std::move(curve));
    }
    const fit::Result r = fit::fit_kinetics(built, curves, problem);
    std::copy(r.value.begin(), r.value.end(), values);
    std::copy(r.standard_error.begin(), r.standard_error.end(), standard_errors);
    if (correlation != nullptr) {
      for (const std::vector<double>& row : r.correlation) correlation = std::copy(row.begin(), row.end(), correlation);
    }
    if (model_force != nullptr) std::copy(r.model_force.begin(), r.model_force.end(), model_force);
    if (residual != nullptr) std::copy(r.residual.begin(), r.residual.end(), residual);
    summary->points = static_cast<int>(r.points);
    summary->iterations = r.iterations;
    summary->simulations = r.solver_calls;
    summary->weighted = r.weighted ? 1 : 0;
    summary->r_squared = r.r_squared;
    summary->chi2_per_dof = r.chi2_per_dof;
    summary->residual_sigma = r.residual_sigma;
    summary->seconds = r.seconds;
  });
}

}  // extern "C"
