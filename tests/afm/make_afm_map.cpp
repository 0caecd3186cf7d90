// Test helper: writes a synthetic JPK force map (.jpk-force-map, the instrument's zip layout:
// header.properties with the grid, shared-data/header.properties with the channels' conversion
// sets through lcd-info, index/N/header.properties with the position, index/N/segments/S/ with
// the segment header and big-endian float channels height and vDeflection) from the library's
// own Hertz model (coatcontact/afm_fit.hpp), and the truth of every curve as a TSV.
//   Each curve: tip positions z from z_c + 3 um down to z_c - 1 um (approach, then the same back
//   as retract), F = E*(x, y) g(z_c - z) on a 10 um sphere (nu = 0.5) + a tilted baseline
//   b0 + s z + Gaussian noise; the retract adds an adhesive dip (pull-off). The height channel
//   is z - F/k, vDeflection F/(k sens). E and z_c vary smoothly over the map.
//   --jkr: the adhesive retract of a film (E1 = 100 kPa, nu1 = 0.5, t = 4 um) on E0 = 1 MPa
//   (nu0 = 0.3) under a k = 1 N/m cantilever, noise 5 nN: the library's JKR spring model
//   (fit::afm_model_force, model jkr) on a uniform piezo grid, the tip leaving at the jump-off
//   (so the tip axis has its gap), w in {8, 10, 12, 14} mJ/m2 by (i + j) % 4; the approach is the
//   adhesionless model of the same coating. The truth file gains a column w; the jump-in curves
//   (n % 16 == 7) expect no flag, since a retract fit does not look at the approach's jump-in.
//   --md: the same coating, cantilever and w pattern with the library's Maugis-Dugdale spring
//   model (fit::afm_model_force, model md, surface-force range z0 = 0.5 um: Maugis's lambda
//   ~0.7-1.2, between DMT and JKR) and a film modulus E1 that varies smoothly over the map
//   (100 kPa +- 20 %); the approach is the adhesionless model of each curve's coating. E1 is
//   read (as the fit reads it with E1 free) between the nodes E0 10^(j/8) of the model's tables.
//   --rigid (with --md): the same film on a rigid base (one table, E1 a pure scale).
//   --back-and-forth: the meander scan of the instrument's maps (every real JPK map in
//   data/afm/): curve n runs row j = n / NX backwards when j is odd, so its grid x is
//   NX - 1 - n % NX (header key position-pattern.back-and-forth=true; false without the option).
//   Bad curves (unless --clean), by curve index n: n % 16 == 3 never reaches the sample
//   (no_contact), n % 16 == 7 has a jump-in dip of -60 sigma before contact (jump_in),
//   n % 16 == 11 has an empty retract segment (empty_segment), n % 16 == 13 has no force
//   calibration slot (calibration).
// Usage: make_afm_map OUT.jpk-force-map NX NY [--points N] [--seed S] [--truth FILE] [--clean] [--jkr|--md [--rigid]] [--back-and-forth]
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "coatcontact/afm_fit.hpp"

namespace fit = coatcontact::fit;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSpring = 0.05;         // k [N/m]
constexpr double kSensitivity = 50e-9;   // [m/V]
constexpr double kNoise = 0.1e-9;        // [N]
constexpr double kRadius = 10e-6;        // [m]
constexpr double kPitch = 2e-6;          // grid pitch [m]
// --jkr: the coating, cantilever and noise of the adhesive maps.
constexpr double kJkrSpring = 1.0, kJkrNoise = 5e-9, kFilm = 100e3, kSubstrate = 1e6, kThickness = 4e-6;
constexpr double kJkrWork[4] = {8e-3, 10e-3, 12e-3, 14e-3};
// --md: the surface-force range z0 [m] (fit with --range 0.5um).
constexpr double kMdRange = 0.5e-6;

fit::AfmFitProblem coating_problem(fit::AfmModel model, double work, double film = kFilm, bool rigid = false) {
  fit::AfmFitProblem p;
  p.model = model;
  p.tip = fit::afm_paraboloid(kRadius);
  fit::AfmCoating c;
  c.film = {film, 0.5};
  c.substrate.material = {kSubstrate, 0.3};
  c.substrate.rigid = rigid;
  c.thickness = kThickness;
  p.coating = c;
  p.poisson = 0.5;
  p.work = work;
  p.spring_constant = kJkrSpring;
  if (model == fit::AfmModel::kMd) p.surface_force_range = kMdRange;
  return p;
}

// The spring-stable JKR (or Maugis-Dugdale) branch at z_c = 0: indentation, force and base coordinate
// Z = delta + F/k (increasing along the branch), from its jump-off to 2 um.
struct JkrBranch {
  std::vector<double> delta, force, base;
  // (delta, F) where Z = target on the branch (linear between its 6000 points); false below
  // the jump-off.
  bool at(double target, double& d, double& f) const {
    if (target < base.front()) return false;
    const auto it = std::upper_bound(base.begin(), base.end(), target);
    const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(it - base.begin()), base.size() - 1);
    const std::size_t a = k == 0 ? 0 : k - 1;
    const double x = base[k] > base[a] ? std::clamp((target - base[a]) / (base[k] - base[a]), 0.0, 1.0) : 0.0;
    d = delta[a] + x * (delta[k] - delta[a]);
    f = force[a] + x * (force[k] - force[a]);
    return true;
  }
};

JkrBranch jkr_branch(double work, fit::AfmModel model = fit::AfmModel::kJkr, double film = kFilm, bool rigid = false) {
  std::vector<double> z;
  for (int k = 0; k < 6000; ++k) z.push_back(1e-6 - 3e-6 * k / 5999.0);
  const std::vector<double> f = fit::afm_model_force(coating_problem(model, work, film, rigid), z);
  JkrBranch b;
  for (std::size_t k = 0; k < z.size(); ++k) {
    if (f[k] == 0.0) continue;  // off the sample
    b.delta.push_back(-z[k]);
    b.force.push_back(f[k]);
    b.base.push_back(-z[k] + f[k] / kJkrSpring);
  }
  return b;
}

// Truth of curve (i, j) of an nx x ny map.
double modulus_at(long i, long j, long nx, long ny) {
  return 5e3 * (1.0 + 0.4 * std::sin(2.0 * kPi * (i + 0.5) / nx) * std::cos(kPi * (j + 0.5) / ny));
}
// The adhesionless approach of the coating with film modulus `film` on the tip grid relative to
// the contact point (z_c + 3 um down to z_c - 1 um).
std::vector<double> coated_approach_force(double film, std::size_t points, bool rigid = false) {
  std::vector<double> z(points);
  for (std::size_t p = 0; p < points; ++p) z[p] = 3e-6 - 4e-6 * static_cast<double>(p) / static_cast<double>(points - 1);
  return fit::afm_model_force(coating_problem(fit::AfmModel::kHertz, 0.0, film, rigid), z);
}

// --md: E1 over the map.
double md_film_at(long i, long j, long nx, long ny) {
  return kFilm * (1.0 + 0.2 * std::sin(2.0 * kPi * (i + 0.5) / nx) * std::cos(kPi * (j + 0.5) / ny));
}
double contact_at(long i, long j) { return 3e-6 + 0.02e-6 * i - 0.01e-6 * j; }  // a tilted sample

class Archive {
 public:
  explicit Archive(const std::string& path) : path_(path) { open(ZIP_CREATE | ZIP_TRUNCATE); }
  ~Archive() { close(); }
  void add(const std::string& name, std::string data) {
    // libzip frees a buffer it was given only when it holds bytes: an empty entry gets none.
    char* copy = nullptr;
    if (!data.empty()) {
      copy = static_cast<char*>(std::malloc(data.size()));
      std::memcpy(copy, data.data(), data.size());
    }
    zip_source_t* source = zip_source_buffer(archive_, copy, data.size(), copy != nullptr ? 1 : 0);
    const zip_int64_t index = zip_file_add(archive_, name.c_str(), source, ZIP_FL_OVERWRITE);
    if (index < 0) die("cannot add " + name);
    zip_set_file_compression(archive_, static_cast<zip_uint64_t>(index), ZIP_CM_STORE, 0);
    pending_ += data.size();
    // Written out now and then, so the writer's memory stays bounded for big maps.
    if (pending_ > (64u << 20)) {
      close();
      open(0);
    }
  }
  void close() {
    if (archive_ != nullptr && zip_close(archive_) != 0) die(std::string("cannot write the archive: ") + zip_strerror(archive_));
    archive_ = nullptr;
    pending_ = 0;
  }

 private:
  void open(int flags) {
    int error = 0;
    archive_ = zip_open(path_.c_str(), flags, &error);
    if (archive_ == nullptr) die("cannot create " + path_);
  }
  [[noreturn]] static void die(const std::string& message) {
    std::fprintf(stderr, "make_afm_map: %s\n", message.c_str());
    std::exit(1);
  }
  std::string path_;
  zip_t* archive_ = nullptr;
  std::size_t pending_ = 0;
};

std::string big_endian_floats(const std::vector<double>& values) {
  std::string bytes(values.size() * 4, '\0');
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float v = static_cast<float>(values[i]);
    std::uint32_t u = 0;
    std::memcpy(&u, &v, 4);
    for (int b = 0; b < 4; ++b) bytes[4 * i + b] = static_cast<char>((u >> (24 - 8 * b)) & 0xffu);
  }
  return bytes;
}

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// lcd-info 0: height (volts -> nominal [m], multiplier 1); 1: vDeflection (volts -> distance
// [m] by the sensitivity -> force [N] by k); 2: the same without its force slot.
std::string shared_header(double spring) {
  std::string s;
  s += "lcd-info.0.type=float-data\nlcd-info.0.channel.name=height\nlcd-info.0.unit.unit=V\n";
  s += "lcd-info.0.conversion-set.conversions.list=nominal\nlcd-info.0.conversion-set.conversions.base=volts\n";
  s += "lcd-info.0.conversion-set.conversion.nominal.defined=true\n";
  s += "lcd-info.0.conversion-set.conversion.nominal.base-calibration-slot=volts\n";
  s += "lcd-info.0.conversion-set.conversion.nominal.scaling.offset=0.0\n";
  s += "lcd-info.0.conversion-set.conversion.nominal.scaling.multiplier=1.0\n";
  s += "lcd-info.0.conversion-set.conversion.nominal.scaling.unit.unit=m\n";
  for (int info : {1, 2}) {
    const std::string p = "lcd-info." + std::to_string(info) + ".";
    s += p + "type=float-data\n" + p + "channel.name=vDeflection\n" + p + "unit.unit=V\n";
    s += p + "conversion-set.conversions.list=distance force\n" + p + "conversion-set.conversions.base=volts\n";
    s += p + "conversion-set.conversion.distance.defined=true\n";
    s += p + "conversion-set.conversion.distance.base-calibration-slot=volts\n";
    s += p + "conversion-set.conversion.distance.scaling.offset=0.0\n";
    s += p + "conversion-set.conversion.distance.scaling.multiplier=" + number(kSensitivity) + "\n";
    s += p + "conversion-set.conversion.distance.scaling.unit.unit=m\n";
    if (info == 1) {
      s += p + "conversion-set.conversion.force.defined=true\n";
      s += p + "conversion-set.conversion.force.base-calibration-slot=distance\n";
      s += p + "conversion-set.conversion.force.scaling.offset=0.0\n";
      s += p + "conversion-set.conversion.force.scaling.multiplier=" + number(spring) + "\n";
      s += p + "conversion-set.conversion.force.scaling.unit.unit=N\n";
    } else {
      s += p + "conversion-set.conversion.force.defined=false\n";
    }
  }
  return s;
}

std::string segment_header(std::size_t points, const char* style, int deflection_info) {
  std::string s;
  s += "force-segment-header.num-points=" + std::to_string(points) + "\n";
  s += "force-segment-header.duration=1.0\n";
  s += std::string("force-segment-header.settings.style=") + style + "\n";
  s += "channels.list=height vDeflection\n";
  s += "channel.height.lcd-info.*=0\nchannel.height.data.file.name=channels/height.dat\n";
  s += "channel.height.data.file.format=raw\nchannel.height.data.num-points=" + std::to_string(points) + "\n";
  s += "channel.vDeflection.lcd-info.*=" + std::to_string(deflection_info) + "\n";
  s += "channel.vDeflection.data.file.name=channels/vDeflection.dat\n";
  s += "channel.vDeflection.data.file.format=raw\nchannel.vDeflection.data.num-points=" + std::to_string(points) + "\n";
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: make_afm_map OUT.jpk-force-map NX NY [--points N] [--seed S] [--truth FILE] [--clean] [--jkr|--md [--rigid]] [--back-and-forth]\n");
    return 2;
  }
  const std::string out = argv[1];
  const long nx = std::atol(argv[2]), ny = std::atol(argv[3]);
  std::size_t points = 400;
  unsigned long seed = 1;
  std::string truth_path;
  bool clean = false, jkr = false, md = false, rigid = false, meander = false;
  for (int a = 4; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--points" && a + 1 < argc) points = static_cast<std::size_t>(std::atol(argv[++a]));
    else if (arg == "--seed" && a + 1 < argc) seed = std::strtoul(argv[++a], nullptr, 10);
    else if (arg == "--truth" && a + 1 < argc) truth_path = argv[++a];
    else if (arg == "--clean") clean = true;
    else if (arg == "--jkr") jkr = true;
    else if (arg == "--md") jkr = md = true;  // the --jkr map with the Maugis-Dugdale model
    else if (arg == "--rigid") rigid = true;
    else if (arg == "--back-and-forth") meander = true;
    else {
      std::fprintf(stderr, "make_afm_map: unknown argument %s\n", arg.c_str());
      return 2;
    }
  }
  if (rigid && !md) {
    std::fprintf(stderr, "make_afm_map: --rigid goes with --md\n");
    return 2;
  }
  if (nx < 1 || ny < 1 || points < 20) {
    std::fprintf(stderr, "make_afm_map: need NX, NY >= 1 and --points >= 20\n");
    return 2;
  }
  const double spring = jkr ? kJkrSpring : kSpring, noise_sigma = jkr ? kJkrNoise : kNoise;
  std::ofstream truth;
  if (!truth_path.empty()) {
    truth.open(truth_path);
    truth << "# synthetic JPK force map written by tests/afm/make_afm_map (truth of each curve)\n"
          << "# sphere R = " << number(kRadius) << " m, nu = 0.5, k = " << number(spring) << " N/m, sensitivity = "
          << number(kSensitivity) << " m/V, noise sigma = " << number(noise_sigma) << " N, points per segment = " << points << "\n";
    if (md) {
      truth << "# Maugis-Dugdale retract on a coating (z0 = " << number(kMdRange) << " m): film E1 (column E), nu1 = 0.5, t = "
            << number(kThickness) << " m, substrate "
            << (rigid ? std::string("rigid") : "E0 = " + number(kSubstrate) + " Pa, nu0 = 0.3") << "\n";
    } else if (jkr) {
      truth << "# JKR retract on a coating: film E1 (column E), nu1 = 0.5, t = " << number(kThickness) << " m, substrate E0 = "
            << number(kSubstrate) << " Pa, nu0 = 0.3\n";
    }
    if (jkr) {
      truth << "# columns: curve\tgrid_x\tgrid_y\tE\tcontact_point\tbaseline_at_contact\tbaseline_slope\texpected_flag\tw\n"
            << "# units: -\t-\t-\tPa\tm\tN\tN/m\t-\tJ/m2\n";
    } else {
      truth << "# columns: curve\tgrid_x\tgrid_y\tE\tcontact_point\tbaseline_at_contact\tbaseline_slope\texpected_flag\n"
            << "# units: -\t-\t-\tPa\tm\tN\tN/m\t-\n";
    }
  }
  // --jkr: the branches of the four w, and the approach (adhesionless, the same coating) on the
  // tip grid relative to the contact point (the same for every curve).
  std::vector<JkrBranch> branches;
  std::vector<double> coated_approach;
  if (jkr && !md) {
    for (double w : kJkrWork) branches.push_back(jkr_branch(w));
    coated_approach = coated_approach_force(kFilm, points);
  }
  Archive archive(out);
  archive.add("header.properties",
              "type=force-scan-map\nforce-scan-map.description.instrument=synthetic (coatcontact tests)\n"
              "force-scan-map.position-pattern.grid.ilength=" + std::to_string(nx) +
                  "\nforce-scan-map.position-pattern.grid.jlength=" + std::to_string(ny) +
                  "\nforce-scan-map.position-pattern.grid.ulength=" + number(kPitch * nx) +
                  "\nforce-scan-map.position-pattern.grid.vlength=" + number(kPitch * ny) +
                  "\nforce-scan-map.position-pattern.back-and-forth=" + (meander ? "true" : "false") + "\n");
  archive.add("shared-data/header.properties", shared_header(spring));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (long n = 0; n < nx * ny; ++n) {
    const long j = n / nx, i = meander && j % 2 == 1 ? nx - 1 - n % nx : n % nx;
    const int kind = clean ? -1 : static_cast<int>(n % 16);
    const double modulus = md ? md_film_at(i, j, nx, ny) : jkr ? kFilm : modulus_at(i, j, nx, ny);
    const double work = kJkrWork[(i + j) % 4];
    // --md: each curve's own E1 (its branch and approach); --jkr: one E1, four branches.
    const JkrBranch own_branch = md && kind != 3 ? jkr_branch(work, fit::AfmModel::kMd, modulus, rigid) : JkrBranch{};
    if (md) coated_approach = coated_approach_force(modulus, points, rigid);
    double contact = contact_at(i, j);
    const double slope = 2e-4 * (1.0 + 0.1 * std::sin(0.7 * n));  // [N/m] tilt of the baseline
    const double offset = 1e-9 * std::cos(0.3 * n);
    fit::AfmFitProblem truth_problem;
    truth_problem.tip = fit::afm_paraboloid(kRadius);
    truth_problem.modulus = modulus;
    truth_problem.poisson = 0.5;
    truth_problem.contact_point = contact;
    truth_problem.baseline = 0.0;
    std::vector<double> z(points);
    const double top = contact + 3e-6, bottom = contact - 1e-6;
    for (std::size_t p = 0; p < points; ++p) z[p] = top + (bottom - top) * static_cast<double>(p) / static_cast<double>(points - 1);
    if (kind == 3) {  // the sample is out of reach
      truth_problem.contact_point = bottom - 1e-6;
      contact = truth_problem.contact_point;
    }
    const std::vector<double> model = jkr ? (kind == 3 ? std::vector<double>(points, 0.0) : coated_approach)
                                          : fit::afm_model_force(truth_problem, z);
    std::vector<double> f_approach(points), f_retract(points), z_retract(z.rbegin(), z.rend());
    for (std::size_t p = 0; p < points; ++p) {
      f_approach[p] = model[p] + offset + slope * z[p] + noise_sigma * gauss(rng);
      if (kind == 7 && z[p] > contact && z[p] < contact + 0.1e-6) f_approach[p] -= 60.0 * noise_sigma;
    }
    if (jkr) {
      // A uniform piezo grid h from the approach's deepest point up: on the branch while
      // Z = z_c - h is above its jump-off, else off the sample at z = h.
      const JkrBranch& branch = md ? own_branch : branches[static_cast<std::size_t>((i + j) % 4)];
      double d = 0.0, f = 0.0;
      const double deepest = contact - bottom;
      std::size_t top_index = 0;
      while (top_index + 1 < branch.delta.size() && branch.delta[top_index] < deepest) ++top_index;
      const double h_lo = kind == 3 ? bottom : contact - branch.base[top_index], h_hi = top;
      for (std::size_t p = 0; p < points; ++p) {
        const double h = h_lo + (h_hi - h_lo) * static_cast<double>(p) / static_cast<double>(points - 1);
        double zr = h, fr = 0.0;
        if (kind != 3 && branch.at(contact - h, d, f)) zr = contact - d, fr = f;
        z_retract[p] = zr;
        f_retract[p] = fr + offset + slope * zr + noise_sigma * gauss(rng);
      }
    } else {
      for (std::size_t p = 0; p < points; ++p) {
        const double zr = z_retract[p];
        const double dip = -3e-9 * std::exp(-0.5 * std::pow((zr - (contact + 0.05e-6)) / 0.05e-6, 2));
        f_retract[p] = model[points - 1 - p] + dip + offset + slope * zr + kNoise * gauss(rng);
      }
    }
    const std::string folder = "index/" + std::to_string(n) + "/";
    archive.add(folder + "header.properties",
                "type=force-scan-series\nforce-scan-series.header.position.x=" + number(kPitch * i) +
                    "\nforce-scan-series.header.position.y=" + number(kPitch * j) +
                    "\nforce-scan-series.header.position-index=" + std::to_string(n) + "\n");
    const int deflection_info = kind == 13 ? 2 : 1;
    for (int s = 0; s < 2; ++s) {
      const std::vector<double>& zs = s == 0 ? z : z_retract;
      const std::vector<double>& fs = s == 0 ? f_approach : f_retract;
      const std::size_t count = (kind == 11 && s == 1) ? 0 : points;
      std::vector<double> height(count), volts(count);
      for (std::size_t p = 0; p < count; ++p) {
        height[p] = zs[p] - fs[p] / spring;
        volts[p] = fs[p] / (spring * kSensitivity);
      }
      const std::string seg = folder + "segments/" + std::to_string(s) + "/";
      archive.add(seg + "segment-header.properties", segment_header(count, s == 0 ? "extend" : "retract", deflection_info));
      archive.add(seg + "channels/height.dat", big_endian_floats(height));
      archive.add(seg + "channels/vDeflection.dat", big_endian_floats(volts));
    }
    if (truth) {
      // (--jkr fits the retract: the approach's jump-in does not concern it)
      const int expected = kind == 3 ? 1 : kind == 7 && !jkr ? 2 : kind == 11 ? 4 : kind == 13 ? 6 : 0;
      truth << n << '\t' << i << '\t' << j << '\t' << number(modulus) << '\t' << number(contact) << '\t'
            << number(offset + slope * contact) << '\t' << number(slope) << '\t' << expected;
      if (jkr) truth << '\t' << number(work);
      truth << '\n';
    }
  }
  archive.close();
  return 0;
}
