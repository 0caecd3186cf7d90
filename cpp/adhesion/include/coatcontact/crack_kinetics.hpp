// Rate-dependent JKR adhesion: the contact edge of a sphere or a cone on a coating moves at the
// speed that a crack-kinetics law assigns to G - w (THEORY.md section 14), driven through a spring.
//
// Reduced units (section 14): a_bar = a/L_a, D = delta/L_D, P = F/F_s, Z = z/L_D,
// tau = t v*/L_a (so d a_bar/d tau = (da/dt)/v*), G/w; the sphere's L_a, L_D, F_s = pi w R are
// Maugis's, the cone's are its own (section 14, "The cone"). Built on the interpolated reduced
// variables of an AdhesiveModel (the JKR table: Pi_s, Delta_s for the sphere, Pi_c, Delta_c for
// the cone), so every stack the table serves works.
//
// Thread safety: as AdhesiveModel (its table fills lazily); one model per thread.
#pragma once
#include <limits>
#include <string>
#include <vector>

#include "coatcontact/adhesion.hpp"

namespace coatcontact {

// The indenters the JKR table serves: the paraboloid (Pi_s, Delta_s) and the cone (Pi_c, Delta_c).
enum class KineticsTip { kSphere, kCone };

// G - w = w (|v|/v*)^n for a receding edge, w - G = w (v/v_a*)^n_adv for an advancing one.
struct KineticLaw {
  double n = 0.6;                // > 0
  double n_adv = 0.6;            // > 0
  double speed_ratio_adv = 1.0;  // v_a*/v* > 0
};

// One piece of the drive. The drive variable X is the base position Z (spring or displacement
// control) or the load P itself (load control, k_bar = 0); `rate` is |dX/dtau| > 0.
struct DriveSegment {
  enum class Kind { kApproach, kDwell, kRetract };
  Kind kind = Kind::kApproach;
  double rate = 0.0;       // approach/retract: |dX/dtau|
  double duration = 0.0;   // dwell: tau
  double target_load = 0.0;  // approach: P to reach; retract: P to reach if has_target
  bool has_target = false;   // a retract without target runs until contact is lost
};

struct KineticsOptions {
  double relative_tolerance = 1e-9;  // of the stepper (gsl_odeiv2 msbdf), on a_bar
  double absolute_tolerance = 1e-12;
  // Contact is lost when a_bar falls to this value (<= 0: 1e-2 min(1, r) for the sphere,
  // 1e-2 min(1, max(r_c, 1e-2 eta)) for the cone, section 14).
  double a_bar_end = 0.0;
  // Upper a_bar bound of an approach (<= 0: 100 max(1, r) for the sphere, 1e4 max(1, r_c) for
  // the cone, within the table's range); an approach past it is InputError.
  double a_bar_max = 0.0;
  std::size_t max_steps = 2000000;  // NumericalError beyond
};

// One state along the run (every accepted step and every event).
struct KineticsSample {
  double tau = 0.0, drive = 0.0;  // X: Z (spring/displacement control) or P (load control)
  double z = 0.0;                 // base position Z (load control: D + 0, i.e. D)
  double penetration = 0.0;       // D
  double a_bar = 0.0;
  double load = 0.0;              // P
  double g_over_w = 0.0;          // G/w (0 on the adhesionless curve)
  int segment = 0;                // index into the protocol
  bool on_hertz = false;          // edge under compression: on the adhesionless curve
};

struct KineticsEvent {
  double tau = 0.0, load = 0.0, a_bar = 0.0, penetration = 0.0, z = 0.0;
};

struct KineticsResult {
  std::vector<KineticsSample> samples;
  // Most tensile P of the last retract (as an instrument reads the pull-off).
  KineticsEvent pulloff;
  // Where a_bar reaches a_bar_end.
  KineticsEvent loss;
  // Energy (section 14), in units of pi w L_a^2: drive work W = int P dX (spring/
  // displacement: int P dZ; load control: int P dD), dissipation -int 2 (G/w - 1) a_bar da_bar,
  // stored energy at the start and at the end.
  double work = 0.0, dissipation = 0.0, energy_start = 0.0, energy_end = 0.0;
  std::size_t steps = 0;          // accepted ODE steps
  std::vector<std::string> warnings;
};

// Stored energy E/(pi w L_a^2) = U_el(a_bar, D) + P^2/(2 k_bar) - a_bar^2 (section 14).
double kinetics_energy(const AdhesiveModel& model, double eta, double a_bar, double penetration,
                       double load, double k_bar, KineticsTip tip = KineticsTip::kSphere);

// Simulates the protocol from first contact (a_bar = a_bar_end on the adhesionless curve,
// tau = 0) to the loss of contact. k_bar >= 0: 0 is load control, +inf displacement control.
// InputError (message naming the segment) for a bad law, k_bar, protocol or a target never
// reached; NumericalError when the stepper fails.
KineticsResult simulate_kinetics(const AdhesiveModel& model, double eta, const KineticLaw& law,
                                 double k_bar, const std::vector<DriveSegment>& protocol,
                                 const KineticsOptions& options = {});
KineticsResult simulate_kinetics(const AdhesiveModel& model, KineticsTip tip, double eta,
                                 const KineticLaw& law, double k_bar,
                                 const std::vector<DriveSegment>& protocol,
                                 const KineticsOptions& options = {});

// The same protocol for each rate of its last segment (a retract until contact is lost); the
// part before it is simulated once. Each result keeps its samples only if keep_samples.
std::vector<KineticsResult> sweep_kinetics(const AdhesiveModel& model, double eta,
                                           const KineticLaw& law, double k_bar,
                                           const std::vector<DriveSegment>& protocol,
                                           const std::vector<double>& retract_rates,
                                           bool keep_samples = false,
                                           const KineticsOptions& options = {});
std::vector<KineticsResult> sweep_kinetics(const AdhesiveModel& model, KineticsTip tip, double eta,
                                           const KineticLaw& law, double k_bar,
                                           const std::vector<DriveSegment>& protocol,
                                           const std::vector<double>& retract_rates,
                                           bool keep_samples = false,
                                           const KineticsOptions& options = {});

// ---- SI layer: a sphere of radius R or a cone of half angle beta on a coating of thickness t
// (THEORY.md section 14) ----

// One protocol segment in SI: approach/retract at `speed` (m/s; N/s under load control) until
// the force reaches `target_force` (N; a retract without target runs until contact is lost),
// or a dwell of `duration` (s).
struct KineticsSegmentSI {
  DriveSegment::Kind kind = DriveSegment::Kind::kApproach;
  double speed = 0.0, duration = 0.0, target_force = 0.0;
  bool has_target = false;
};

struct KineticsSetupSI {
  KineticsTip tip = KineticsTip::kSphere;
  double radius = 0.0;      // m, the sphere's
  double half_angle = 0.0;  // rad in (0, pi/2), the cone's half included angle
  double thickness = 0.0, work = 0.0;  // m, J/m^2
  double v_star = 0.0, n = 0.0;                     // m/s, receding law
  double v_star_adv = 0.0, n_adv = 0.0;             // <= 0: the receding values
  double spring = 0.0;                              // N/m; 0 load control, +inf displacement
  std::vector<KineticsSegmentSI> protocol;
};

struct KineticsEventSI {
  double force = 0.0, time = 0.0, radius = 0.0;  // N, s, m
};

struct KineticsScales {
  double length = 0.0, penetration = 0.0, force = 0.0, time = 0.0;  // L_a, L_D, F_s, L_a/v*
  double eta = 0.0, k_bar = 0.0;
  double drive_rate = 0.0;  // reduced drive rate per SI speed (per m/s, or per N/s)
};

struct KineticsResultSI {
  std::vector<double> t, z, delta, a, force, g;  // s, m, m, m, N, J/m^2 (z: delta under load control)
  KineticsEventSI pulloff, loss;
  double retract_speed = 0.0;  // of the last segment
  KineticsResult reduced;      // the run in reduced units
};

// Scales of a setup; InputError naming the parameter for anything out of range.
KineticsScales kinetics_scales(const AdhesiveModel& model, const KineticsSetupSI& setup);
// One run per retract speed of the last segment (the setup's own if `retract_speeds` is empty);
// samples only if keep_samples (always for a single run).
std::vector<KineticsResultSI> simulate_kinetics_si(const AdhesiveModel& model, const KineticsSetupSI& setup,
                                                   const std::vector<double>& retract_speeds = {},
                                                   bool keep_samples = true,
                                                   const KineticsOptions& options = {});

}  // namespace coatcontact
