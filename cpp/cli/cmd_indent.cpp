// `coatcontact indent show`: nanoindentation files (cpp/measure/indent/) read into SI, one test
// as TSV with its calibration and metadata in the header; the `indent` dispatcher over the
// table of sub-subcommands (indent_commands.hpp).
#include <cmath>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/indentation.hpp"
#include "commands.hpp"
#include "indent_commands.hpp"

namespace coatcontact::cli {

namespace {

// The sub-subcommands of `indent`; a new one is one line here and its declaration in
// indent_commands.hpp.
const IndentCommand kIndentCommands[] = {
    {"show", run_indent_show, "the channels of one test as TSV in SI, calibration and metadata in the header"},
    {"analyse", run_indent_analyse, "Oliver-Pharr: E and H per depth and over a range (one test or --all)"},
    {"calibrate", run_indent_calibrate, "the tip's area function and the frame compliance on a reference"},
    {"film", run_indent_film, "the film's modulus (or thickness) from the exact coated stiffness, and the empirical models"},
};

constexpr const char* kIndentFormats =
    "Formats (chosen by content and extension): Agilent/KLA NanoSuite .xls (one sheet per test),\n"
    "Hysitron .txt and .hld, Micromaterials .zip (one text file per indent), FischerScope .txt\n"
    "(decimal commas). Units: SI (m, N, s, N/m, Pa).";

const std::vector<OptionSpec> kShowSpec = {
    indent_test_option(),
    indent_index_option(),
    {"--output", "FILE", "write the table to FILE (atomically) instead of stdout", false},
};

std::string join_numbers(const std::vector<double>& values, const std::string& name) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : " ") + format_parameter(v, name);
  return text;
}

}  // namespace

OptionSpec indent_test_option() { return {"--test", "NAME", "the test of that name (\"Test 003\"; `indent show` lists them)", false}; }
OptionSpec indent_index_option() { return {"--index", "N", "the test at index N (0-based; default 0)", false}; }

std::size_t choose_indent_test(const std::vector<indent::IndentTest>& tests, const Arguments& arguments,
                               const std::string& path) {
  const auto name = arguments.get("--test");
  const auto index = arguments.get("--index");
  if (name && index) throw InputError("--test and --index: give one of them, not both");
  const auto listing = [&]() {
    std::string text;
    for (std::size_t i = 0; i < tests.size() && i < 20; ++i) text += (i ? ", '" : "'") + tests[i].name + "'";
    return text + (tests.size() > 20 ? ", ..." : "");
  };
  if (name) {
    for (std::size_t i = 0; i < tests.size(); ++i) if (tests[i].name == *name) return i;
    throw InputError("--test: '" + name->substr(0, 60) + "' is not a test of " + path + "; it holds " + listing());
  }
  if (!index) return 0;
  const double value = parse_number(*index, "--index");
  if (!(value >= 0.0 && value < static_cast<double>(tests.size())) || value != std::floor(value)) {
    throw InputError("--index: '" + index->substr(0, 60) + "' is not allowed; " + path + " holds " + std::to_string(tests.size()) +
                     (tests.size() == 1 ? " test (index 0)" : " tests (indices 0.." + std::to_string(tests.size() - 1) + ")"));
  }
  return static_cast<std::size_t>(value);
}

void add_indent_test_header(std::vector<std::pair<std::string, std::string>>& items,
                            const std::vector<indent::IndentTest>& tests, std::size_t index, const std::string& path) {
  const indent::IndentTest& t = tests.at(index);
  items.push_back({"file", path});
  items.push_back({"test", t.name + " (index " + std::to_string(index) + " of " + std::to_string(tests.size()) + ")"});
  std::string names;  // the first 100 (a file of thousands would make one very long line)
  for (std::size_t i = 0; i < tests.size() && i < 100; ++i) names += (i ? ", " : "") + tests[i].name;
  if (tests.size() > 100) names += ", ... (" + std::to_string(tests.size()) + " in all)";
  if (tests.size() > 1) items.push_back({"tests in the file", names});
  items.push_back({"points", std::to_string(t.depth.size())});
  const indent::Calibration& c = t.calibration;
  const auto stated = [&](const char* key, double value, const char* name) {
    items.push_back({key, std::isnan(value) ? std::string("not stated") : format_parameter(value, name)});
  };
  items.push_back({"area coefficients (A [nm^2] = C0 h^2 + C1 h + C2 h^(1/2) + ..., h_c [nm])",
                   c.area.coefficients.empty() ? std::string("not stated") : join_numbers(c.area.coefficients, "area coefficient")});
  stated("frame stiffness [N/m]", c.frame_stiffness, "frame stiffness");
  stated("poisson (sample)", c.poisson, "poisson");
  items.push_back({"tip", c.tip.empty() ? std::string("not stated") : c.tip});
  stated("beta", c.beta, "beta");
  stated("epsilon", c.eps, "epsilon");
  stated("averaging range from [m]", c.range_min, "range");
  stated("averaging range to [m]", c.range_max, "range");
  if (!c.source.empty()) items.push_back({"calibration from", c.source});
  for (const auto& [key, value] : t.vendor_results) {
    items.push_back({"vendor " + key + (key.find('[') == std::string::npos ? " [Pa]" : ""), format_parameter(value, key)});
  }
  for (const auto& [key, value] : t.metadata) {
    if (key != "test" && key != "file") items.push_back({"file: " + key, value});
  }
  items.push_back({"missing values", "- where the vendor wrote no value (NanoSuite: 1.797e308)"});
}

std::string indent_column_name(const std::string& channel) {
  std::string name = channel;
  const auto open = name.rfind(" [");
  if (open != std::string::npos && name.back() == ']') {
    std::string unit = name.substr(open + 2, name.size() - open - 3);
    for (std::size_t at; (at = unit.find('/')) != std::string::npos;) unit.replace(at, 1, "_per_");
    name = name.substr(0, open) + "_" + unit;
  }
  for (char& ch : name) if (ch == ' ' || ch == '\t') ch = '_';
  return name;
}

std::string indent_cell(double value, const std::string& column) {
  return std::isnan(value) ? std::string("-") : format_value(value, column);
}

int run_indent_show(const Args& args) {
  return run_guarded("indent show", [&]() -> int {
    const Arguments arguments(args, kShowSpec, 1);
    if (arguments.help()) {
      std::cout << usage("indent show", "FILE [--test NAME | --index N] [--output FILE]",
                         "One test of a nanoindentation file as TSV in SI units: depth, load, time,\n"
                         "the CSM contact stiffness and the vendor's hardness and modulus where the\n"
                         "file has them, the segment, then the file's other channels. The header holds\n"
                         "the calibration as the file states it (area function, Poisson's ratio, frame\n"
                         "stiffness, tip, averaging range), the vendor's results and all other metadata,\n"
                         "and lists the file's tests.\n" + std::string(kIndentFormats),
                         kShowSpec);
      return kExitSuccess;
    }
    if (arguments.positionals().size() != 1) throw InputError("expected one FILE (see --help)");
    const std::string path = arguments.positionals().front();
    register_input(path, "indentation file");
    const auto output_path = arguments.get("--output").value_or("");
    check_output_path(output_path, "--output");
    const std::vector<indent::IndentTest> tests = indent::read_indentation(path);
    const std::size_t index = choose_indent_test(tests, arguments, path);
    const indent::IndentTest& t = tests[index];

    std::vector<std::pair<std::string, std::string>> items = {{"coatcontact indent show", "one test of a nanoindentation file in SI units"}};
    add_indent_test_header(items, tests, index, path);
    std::vector<std::string> columns;
    std::vector<const std::vector<double>*> data;
    const std::pair<const char*, const std::vector<double>*> standard[] = {
        {"depth_m", &t.depth},       {"load_N", &t.load},          {"time_s", &t.time},
        {"stiffness_N_per_m", &t.stiffness}, {"hardness_Pa", &t.hardness}, {"modulus_Pa", &t.modulus}};
    for (const auto& [column, values] : standard) {
      if (!values->empty()) columns.push_back(column), data.push_back(values);
    }
    if (!t.segment.empty()) columns.push_back("segment");
    const std::size_t segment_column = t.segment.empty() ? columns.size() : columns.size() - 1;
    for (const auto& [name, values] : t.extra) columns.push_back(indent_column_name(name)), data.push_back(&values);
    Output output(output_path);
    std::ostream& out = output.stream();
    write_header(out, items, columns);
    std::string line;
    for (std::size_t i = 0; i < t.depth.size(); ++i) {
      line.clear();
      for (std::size_t c = 0, d = 0; c < columns.size(); ++c) {
        if (c) line += '\t';
        if (c == segment_column) line += std::to_string(t.segment[i]);
        else line += indent_cell((*data[d++])[i], columns[c]);
      }
      out << line << '\n';
    }
    output.commit();
    return kExitSuccess;
  });
}

int run_indent(const Args& args) {
  std::string overview = "usage: coatcontact indent <command> FILE [options]   (coatcontact indent <command> --help)\n\n"
                         "Nanoindentation files of the vendors, in SI units.\n";
  for (const auto& command : kIndentCommands) overview += "  " + std::string(command.name) + std::string(10 - std::string(command.name).size(), ' ') + command.summary + "\n";
  if (args.empty()) {
    std::cerr << overview;
    return kExitUsage;
  }
  if (args[0] == "--help" || args[0] == "-h") {
    std::cout << overview;
    return kExitSuccess;
  }
  const Args rest(args.begin() + 1, args.end());
  std::string known;
  for (const auto& command : kIndentCommands) {
    if (args[0] == command.name) return command.run(rest);
    known += (known.empty() ? "" : ", ") + std::string(command.name);
  }
  std::cerr << "coatcontact indent: error: unknown indent command '" << args[0].substr(0, 60) << "' (expected " << known << ")\n";
  return kExitUsage;
}

}  // namespace coatcontact::cli
