// Nanoindentation files (cpp/measure/indent/): one entry point, the format chosen by content
// and extension. Every reader converts to SI and fills the same IndentTest.
//   NanoSuite      .xls  Agilent/KLA NanoSuite export (BIFF8 via FreeXL): sheets "Test 001"...,
//                        "Results", "Required Inputs", "Inputs Editable Post Test"
//   Hysitron text  .txt  date, "Number of Points = N", depth [nm], load [µN], time [s], ...
//   Hysitron HLD   .hld  "key: value" header, then channel blocks
//   Micromaterials .zip  one headerless text file per indent: time [s], depth [nm], load [mN]
//   FischerScope   .txt  application export, decimal commas
// Errors are InputError naming the file, the sheet or archive entry and the line (or cell).
#pragma once
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "coatcontact/errors.hpp"

namespace coatcontact::indent {

inline constexpr double kNotGiven = std::numeric_limits<double>::quiet_NaN();

// The tip's area function in the vendors' form, h_c in nm and A in nm^2:
//   A = C0 h^2 + C1 h + C2 h^(1/2) + C3 h^(1/4) + C4 h^(1/8) + ...   (coefficients[k] = Ck)
// Empty when the file states none.
struct AreaFunction {
  std::vector<double> coefficients;
};

// What the file states about the test's calibration and analysis; NaN / empty where it is
// silent (no default is invented here).
struct Calibration {
  AreaFunction area;
  double frame_stiffness = kNotGiven;  // [N/m]
  double poisson = kNotGiven;          // the sample's Poisson ratio
  std::string tip;                     // the tip's name as the file writes it
  double beta = kNotGiven;             // Oliver–Pharr beta, if the file states one
  double eps = kNotGiven;              // epsilon of h_c = h - eps P/S, if stated
  double range_min = kNotGiven;        // [m] the vendor's averaging range of E and H
  double range_max = kNotGiven;        // [m]
  std::string source;                  // where these came from ("Results sheet, ..."), for headers
};

struct IndentTest {
  std::string name;                        // the vendor's test name ("Test 001", entry stem...)
  std::vector<double> depth, load, time;   // [m], [N], [s], same length (time empty if none)
  std::vector<double> stiffness;           // [N/m] CSM harmonic contact stiffness, empty if none
  std::vector<double> hardness, modulus;   // [Pa] the vendor's own columns, empty if none
  std::vector<int> segment;                // segment per point, empty if none (NanoSuite from 1,
                                           // Hysitron text from 0, .hld the header's numbers)
  // In every channel NaN marks a value the vendor wrote as missing (NanoSuite's 1.797e308).
  std::map<std::string, std::vector<double>> extra;  // other channels in SI, named "<name> [unit]"
  Calibration calibration;
  std::map<std::string, std::string> metadata;       // everything else the file states
  // The vendor's own results in SI: pressures [Pa] by name ("E_mean", "H_mean" of NanoSuite's
  // Results sheet; "HM", "HIT", "EIT/(1-vs^2)" of FischerScope), others with their SI unit
  // in the key ("hmax [m]").
  std::map<std::string, double> vendor_results;
};

enum class IndentFormat { kNanoSuiteXls, kHysitronTxt, kHysitronHld, kMicromaterialsZip, kFischerScopeTxt };
const char* indent_format_name(IndentFormat format);

// The format of `path` from its first bytes and its extension; InputError if none fits.
IndentFormat detect_indent_format(const std::string& path);

// Every test in the file, in file order (one for single-test files).
std::vector<IndentTest> read_indentation(const std::string& path);

// The same on bytes held in memory (the fuzz targets; the text and zip formats — the .xls
// reader needs a file); `name` stands for the file in messages and helps detection.
std::vector<IndentTest> read_indentation_from_bytes(const std::string& bytes, const std::string& name);

}  // namespace coatcontact::indent
