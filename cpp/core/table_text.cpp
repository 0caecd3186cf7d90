// The text of the TSV tables (coatcontact/detail/table_text.hpp): one spelling for the CLI's
// commands, the AFM batch table and the C API.
#include "coatcontact/detail/table_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::detail {

std::string table_value(double value, const std::string& column) {
  if (!std::isfinite(value)) {
    throw NumericalError("column '" + column + "': result is " + full_precision(value) + " (not finite)");
  }
  return full_precision(value);  // to_chars(general, 17) == "%.17g", any locale
}

std::string table_parameter(double value, const std::string& name) {
  if (!std::isfinite(value)) {
    throw NumericalError("parameter " + name + " is not a finite number");
  }
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);  // shortest round trip
  return std::string(buffer, result.ptr);
}

std::string table_one_line(const std::string& text) {
  std::string out = text;
  std::replace(out.begin(), out.end(), '\n', ' ');
  std::replace(out.begin(), out.end(), '\r', ' ');
  return out;
}

void write_table_header(std::ostream& out, const std::string& command_line, const HeaderItems& items,
                        const std::vector<std::string>& columns) {
  // The same first line in every output; a command's own "command" item gives way to it.
  const bool have_command_line = !command_line.empty();
  if (have_command_line) out << "# command: " << table_one_line(command_line) << "\n";
  for (const auto& item : items) {
    if (have_command_line && item.first == "command") continue;
    out << "# " << table_one_line(item.first) << ": " << table_one_line(item.second) << "\n";
  }
  // A force column in newtons ("F_N", "F_model_N") makes it an SI table: state the sign.
  const bool si_force = std::any_of(columns.begin(), columns.end(), [](const std::string& c) {
    return c.size() > 2 && c.front() == 'F' && c.compare(c.size() - 2, 2, "_N") == 0;
  });
  if (si_force) out << "# sign convention: F compressive positive (pushing the sphere into the film), tension negative\n";
  out << "# columns:";
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i == 0 ? " " : "\t") << table_one_line(columns[i]);
  out << "\n";
}

void add_stack_header_items(HeaderItems& items, const Stack& stack) {
  const Material& film = stack.top();
  const Substrate& substrate = stack.substrate();
  if (stack.is_multilayer()) {
    // THEORY.md section 12: lengths by the total thickness T, moduli by the top layer's E*.
    const auto& layers = stack.layers();
    for (std::size_t i = 0; i < layers.size(); ++i) {
      const Layer& l = layers[i];
      items.emplace_back("layer " + std::to_string(i + 1) + " (h, E [Pa], nu, E* [Pa], interface below)",
                         table_parameter(l.thickness, "layer h") + ", " +
                             table_parameter(l.material.youngs_modulus, "layer E") + ", " +
                             table_parameter(l.material.poisson_ratio, "layer nu") + ", " +
                             table_parameter(l.material.reduced_modulus(), "layer E*") + ", " +
                             (l.slip_below ? "sliding" : "bonded"));
    }
    items.emplace_back("total thickness T (the unit of q, u, a/T and eta; THEORY.md section 12)",
                       table_parameter(stack.total_thickness(), "T"));
    items.emplace_back("reference modulus [Pa] (top layer E*" +
                           std::string(stack.indenter().rigid ? ")" : ", E_r with the indenter)"),
                       table_parameter(stack.reference_modulus(), "reference modulus"));
  } else {
    items.emplace_back("film E1 [Pa]", table_parameter(film.youngs_modulus, "film E1"));
    items.emplace_back("film nu1", table_parameter(film.poisson_ratio, "film nu1"));
    items.emplace_back("film E1* [Pa]", table_parameter(film.reduced_modulus(), "film E1*"));
  }
  if (substrate.rigid) {
    items.emplace_back("substrate", "rigid");
  } else {
    const Material& m = substrate.material;
    items.emplace_back("substrate E0 [Pa]", table_parameter(m.youngs_modulus, "substrate E0"));
    items.emplace_back("substrate nu0", table_parameter(m.poisson_ratio, "substrate nu0"));
    items.emplace_back("substrate E0* [Pa]", table_parameter(m.reduced_modulus(), "substrate E0*"));
  }
  items.emplace_back("E1*/E0*", table_parameter(stack.modulus_ratio(), "E1*/E0*"));
  if (!stack.indenter().rigid) {  // only then, so that rigid-indenter headers stay as they were
    const Material& m = stack.indenter().material;
    items.emplace_back("indenter E2 [Pa]", table_parameter(m.youngs_modulus, "indenter E2"));
    items.emplace_back("indenter nu2", table_parameter(m.poisson_ratio, "indenter nu2"));
    items.emplace_back("indenter E2* [Pa]", table_parameter(m.reduced_modulus(), "indenter E2*"));
    items.emplace_back("reference modulus E_r [Pa] (1/E_r = 1/E1* + 1/E2*; THEORY.md section 9)",
                       table_parameter(stack.reference_modulus(), "E_r"));
  }
}

}  // namespace coatcontact::detail
