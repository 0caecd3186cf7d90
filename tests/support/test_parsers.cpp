// Unit tests of the value parsers (parse_number, parse_list, parse_quantity, parse_material,
// parse_substrate) and of materials.hpp (validate, modulus_ratio).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/cli_support.hpp"
#include "coatcontact/stack.hpp"

using coatcontact::InputError;
using coatcontact::Material;
using coatcontact::Substrate;
using namespace coatcontact::cli;

namespace {

// A number times a unit factor is one correctly rounded product (tier::kRounding); log
// spacing vs pow(10, ...) is a few ulps of exp/log/pow each (tier::kMachine).
namespace tier = check::tier;

// Regression tests, also registered on their own under these names (tests/support/CMakeLists.txt).

// 0.01:100:5 used to give 1.0000000000000009 and 10.000000000000009 (natural-log spacing);
// decades must be exact so headers and gnuplot keys show the values a user typed.
void regression_list_decade_points_not_exact() {
  const auto grid = parse_list("0.01:100:5", "--q");
  check::that(grid.size() == 5 && grid[2] == 1.0 && grid[3] == 10.0, "0.01:100:5 gives exactly 1 and 10");
}

// "50um" gave 4.9999999999999996e-05 (50 * 1e-6 rounds twice); dividing by the exact power of
// ten gives the double nearest to 5e-5.
void regression_unit_prefix_rounding() {
  check::that(parse_quantity("50um", Quantity::kLength, "--thickness") == 5e-5,
              "parse_quantity('50um', Quantity::kLength, '--thickness') == 5e-5");
  check::that(parse_quantity("3nm", Quantity::kLength, "--thickness") == 3e-9,
              "parse_quantity('3nm', Quantity::kLength, '--thickness') == 3e-9");
  check::that(parse_quantity("40mJ/m2", Quantity::kEnergy, "--work") == 0.04,
              "parse_quantity('40mJ/m2', Quantity::kEnergy, '--work') == 0.04");
}

void test_parse_number() {
  check::that(parse_number("1", "--x") == 1.0, "parse_number('1', '--x') == 1.0");
  check::that(parse_number("-2.5", "--x") == -2.5, "parse_number('-2.5', '--x') == -2.5");
  check::that(parse_number("+3", "--x") == 3.0, "parse_number('+3', '--x') == 3.0");
  check::that(parse_number("1e-3", "--x") == 1e-3, "parse_number('1e-3', '--x') == 1e-3");
  check::that(parse_number("1E3", "--x") == 1000.0, "parse_number('1E3', '--x') == 1000.0");
  check::that(parse_number(".5", "--x") == 0.5, "parse_number('.5', '--x') == 0.5");
  check::that(parse_number("5.", "--x") == 5.0, "parse_number('5.', '--x') == 5.0");
  check::that(parse_number("  7 ", "--x") == 7.0,
              "parse_number(' 7 ', '--x') == 7.0");  // blanks around the value are ignored
  check::that(parse_number("\t7", "--x") == 7.0, "parse_number('t7', '--x') == 7.0");
  check::that(parse_number("0", "--x") == 0.0, "parse_number('0', '--x') == 0.0");
  check::that(parse_number("1.7976931348623157e308", "--x") == std::numeric_limits<double>::max(),
              "parse_number('1.7976931348623157e308', '--x') == std::numeric_limits<double>::max()");

  check::throws<InputError>([&] { (void)(parse_number("", "--tol")); }, {"--tol", "empty"});
  check::throws<InputError>([&] { (void)(parse_number("   ", "--tol")); }, {"--tol", "empty"});
  check::throws<InputError>([&] { (void)(parse_number("abc", "--tol")); },
                            {"--tol", "'abc'", "not a number"});
  check::throws<InputError>([&] { (void)(parse_number("1.5x", "--tol")); }, {"--tol", "'1.5x'"});
  check::throws<InputError>([&] { (void)(parse_number("1 2", "--tol")); }, {"--tol", "'1 2'"});
  check::throws<InputError>([&] { (void)(parse_number("nan", "--tol")); }, {"--tol", "not a finite number"});
  check::throws<InputError>([&] { (void)(parse_number("NaN", "--tol")); }, {"--tol", "not a finite number"});
  check::throws<InputError>([&] { (void)(parse_number("-inf", "--tol")); }, {"--tol", "not a finite number"});
  check::throws<InputError>([&] { (void)(parse_number("Infinity", "--tol")); },
                            {"--tol", "not a finite number"});
  check::throws<InputError>([&] { (void)(parse_number("0x1p3", "--tol")); }, {"--tol", "not a number"});
  check::throws<InputError>([&] { (void)(parse_number("0x10", "--tol")); }, "--tol");
  check::throws<InputError>([&] { (void)(parse_number("1e999", "--tol")); }, {"--tol", "outside the range"});
  check::throws<InputError>([&] { (void)(parse_number("-1e999", "--tol")); }, {"--tol", "outside the range"});
  check::throws<InputError>([&] { (void)(parse_number("1e", "--tol")); }, "--tol");
  check::throws<InputError>([&] { (void)(parse_number("e5", "--tol")); }, "--tol");
  check::throws<InputError>([&] { (void)(parse_number("++1", "--tol")); }, "--tol");
  check::throws<InputError>([&] { (void)(parse_number("+-1", "--tol")); }, "--tol");
  check::throws<InputError>([&] { (void)(parse_number("1,5", "--tol")); }, "--tol");  // no decimal comma
  check::throws<InputError>([&] { (void)(parse_number("--1", "--tol")); }, "--tol");
  check::throws<InputError>([&] { (void)(parse_number(std::string("1\0", 2), "--tol")); },
                            {"--tol", "\\x00"});
}

void test_parse_list() {
  const auto three = parse_list("1,2.5,-3", "--q");
  check::that(three.size() == 3 && three[0] == 1.0 && three[1] == 2.5 && three[2] == -3.0,
              "three.size() == 3 && three[0] == 1.0 && three[1] == 2.5 && three[2] == -3.0");
  const auto spaced = parse_list(" 1 , 2 ", "--q");
  check::that(spaced.size() == 2 && spaced[0] == 1.0 && spaced[1] == 2.0,
              "spaced.size() == 2 && spaced[0] == 1.0 && spaced[1] == 2.0");
  check::that(parse_list("42", "--q").size() == 1, "parse_list('42', '--q').size() == 1");

  // MIN:MAX:N log-spaced, end points exact.
  const auto grid = parse_list("0.01:100:5", "--q");
  check::that(grid.size() == 5, "grid.size() == 5");
  check::that(grid.front() == 0.01 && grid.back() == 100.0, "grid.front() == 0.01 && grid.back() == 100.0");
  for (std::size_t i = 0; i < grid.size(); ++i) {
    check::close(grid[i], std::pow(10.0, -2.0 + static_cast<double>(i)), tier::kMachine,
                 "log-spaced grid point");
  }
  regression_list_decade_points_not_exact();
  const auto single = parse_list("3:3:1", "--q");
  check::that(single.size() == 1 && single[0] == 3.0, "single.size() == 1 && single[0] == 3.0");
  const auto same = parse_list("2:2:4", "--q");
  check::that(same.size() == 4 && same[1] == 2.0 && same[3] == 2.0,
              "same.size() == 4 && same[1] == 2.0 && same[3] == 2.0");
  const auto spaced_range = parse_list(" 1 : 10 : 2 ", "--q");
  check::that(spaced_range.size() == 2 && spaced_range[0] == 1.0 && spaced_range[1] == 10.0,
              "spaced_range.size() == 2 && spaced_range[0] == 1.0 && spaced_range[1] == 10.0");
  // Extreme but legal bounds stay finite and inside [MIN, MAX]; subnormal ones are refused
  // (issue 17: 1e-320 reached the solver as NaN-producing input).
  check::throws<InputError>([&] { (void)(parse_list("4.9e-324:1:10", "--q")); }, {"--q", "too small"});
  check::throws<InputError>([&] { (void)(parse_list("1,1e-320", "--u")); }, {"--u", "too small"});
  check::that(parse_list("0,1", "--u")[0] == 0.0, "parse_list('0,1')[0] == 0");
  const auto wide = parse_list("2.2250738585072014e-308:1.7976931348623157e308:1000", "--q");
  bool inside = wide.size() == 1000;
  for (std::size_t i = 0; i < wide.size(); ++i) {
    inside = inside && std::isfinite(wide[i]) && wide[i] > 0.0 && (i == 0 || wide[i] >= wide[i - 1]);
  }
  check::that(inside, "inside");
  check::that(parse_list("1:2:1000000", "--q").size() == 1000000,
              "parse_list('1:2:1000000', '--q').size() == 1000000");

  const char* kExpected = "expected comma-separated numbers or MIN:MAX:N";
  check::throws<InputError>([&] { (void)(parse_list("1,,2", "--q")); },
                            "--q: '1,,2' has an empty item; expected comma-separated numbers or MIN:MAX:N");
  check::throws<InputError>([&] { (void)(parse_list(",1", "--q")); }, {"--q", "empty item"});
  check::throws<InputError>([&] { (void)(parse_list("1,", "--q")); }, {"--q", "empty item"});
  check::throws<InputError>([&] { (void)(parse_list("", "--q")); }, {"--q", "empty", kExpected});
  check::throws<InputError>([&] { (void)(parse_list("1,x", "--q")); }, {"--q", "'x'", kExpected});
  check::throws<InputError>([&] { (void)(parse_list("1,nan", "--q")); }, {"--q", "not a finite number"});
  check::throws<InputError>([&] { (void)(parse_list("1,inf", "--q")); }, {"--q", "not a finite number"});
  check::throws<InputError>([&] { (void)(parse_list("1:2", "--q")); }, {"--q", "MIN:MAX:N"});
  check::throws<InputError>([&] { (void)(parse_list("1:2:3:4", "--q")); }, {"--q", "MIN:MAX:N"});
  check::throws<InputError>([&] { (void)(parse_list("1:10:0", "--q")); }, {"--q", "N '0'", "1 to 1000000"});
  check::throws<InputError>([&] { (void)(parse_list("1:10:1000001", "--q")); }, {"--q", "N '1000001'"});
  check::throws<InputError>([&] { (void)(parse_list("1:10:99999999999999999999", "--q")); }, {"--q", "N "});
  check::throws<InputError>([&] { (void)(parse_list("1:10:2.5", "--q")); }, {"--q", "N '2.5'"});
  check::throws<InputError>([&] { (void)(parse_list("1:10:-3", "--q")); }, {"--q", "N '-3'"});
  check::throws<InputError>([&] { (void)(parse_list("1:10:", "--q")); }, {"--q", "N ''"});
  check::throws<InputError>([&] { (void)(parse_list("0:10:5", "--q")); }, {"--q", "must be > 0"});
  check::throws<InputError>([&] { (void)(parse_list("-1:10:5", "--q")); }, {"--q", "must be > 0"});
  check::throws<InputError>([&] { (void)(parse_list("10:1:5", "--q")); },
                            {"--q", "MIN 10 is larger than MAX 1"});
  check::throws<InputError>([&] { (void)(parse_list("1:10:1", "--q")); }, {"--q", "N = 1", "MIN == MAX"});
  check::throws<InputError>([&] { (void)(parse_list("x:10:5", "--q")); }, {"--q", "MIN 'x'"});
  check::throws<InputError>([&] { (void)(parse_list("1:nan:5", "--q")); }, {"--q", "MAX 'nan'"});
  check::throws<InputError>([&] { (void)(parse_list(":10:5", "--q")); }, {"--q", "MIN is empty"});
  check::throws<InputError>([&] { (void)(parse_list("1:1e999:5", "--q")); }, {"--q", "outside the range"});
}

void test_parse_quantity() {
  check::that(parse_quantity("2MPa", Quantity::kPressure, "--E") == 2e6,
              "parse_quantity('2MPa', Quantity::kPressure, '--E') == 2e6");
  check::that(parse_quantity("2 MPa", Quantity::kPressure, "--E") == 2e6,
              "parse_quantity('2 MPa', Quantity::kPressure, '--E') == 2e6");
  check::that(parse_quantity("1e6", Quantity::kPressure, "--E") == 1e6,
              "parse_quantity('1e6', Quantity::kPressure, '--E') == 1e6");
  check::that(parse_quantity("3Pa", Quantity::kPressure, "--E") == 3.0,
              "parse_quantity('3Pa', Quantity::kPressure, '--E') == 3.0");
  check::that(parse_quantity("1.5kPa", Quantity::kPressure, "--E") == 1500.0,
              "parse_quantity('1.5kPa', Quantity::kPressure, '--E') == 1500.0");
  check::that(parse_quantity("70GPa", Quantity::kPressure, "--E") == 7e10,
              "parse_quantity('70GPa', Quantity::kPressure, '--E') == 7e10");
  check::that(parse_quantity("2e3MPa", Quantity::kPressure, "--E") == 2e9,
              "parse_quantity('2e3MPa', Quantity::kPressure, '--E') == 2e9");
  check::close(parse_quantity("1.5um", Quantity::kLength, "--R"), 1.5e-6, tier::kRounding, "1.5um");
  check::close(parse_quantity("1.5\xc2\xb5m", Quantity::kLength, "--R"), 1.5e-6, tier::kRounding,
               "1.5\xc2\xb5m");
  check::close(parse_quantity("1.5 \xce\xbcm", Quantity::kLength, "--R"), 1.5e-6, tier::kRounding,
               "1.5 \xce\xbcm");
  check::close(parse_quantity("20nm", Quantity::kLength, "--R"), 2e-8, tier::kRounding, "20nm");
  check::close(parse_quantity("5mm", Quantity::kLength, "--R"), 5e-3, tier::kRounding, "5mm");
  check::that(parse_quantity("2m", Quantity::kLength, "--R") == 2.0,
              "parse_quantity('2m', Quantity::kLength, '--R') == 2.0");
  check::close(parse_quantity("50mJ/m2", Quantity::kEnergy, "--w"), 0.05, tier::kRounding, "50mJ/m2");
  check::that(parse_quantity("0.05 J/m2", Quantity::kEnergy, "--w") == 0.05,
              "parse_quantity('0.05 J/m2', Quantity::kEnergy, '--w') == 0.05");
  check::close(parse_quantity("3mN", Quantity::kForce, "--P"), 3e-3, tier::kRounding, "3mN");
  check::close(parse_quantity("3uN", Quantity::kForce, "--P"), 3e-6, tier::kRounding, "3uN");
  check::close(parse_quantity("3\xc2\xb5N", Quantity::kForce, "--P"), 3e-6, tier::kRounding, "3\xc2\xb5N");
  check::close(parse_quantity("3nN", Quantity::kForce, "--P"), 3e-9, tier::kRounding, "3nN");
  check::that(parse_quantity("3N", Quantity::kForce, "--P") == 3.0,
              "parse_quantity('3N', Quantity::kForce, '--P') == 3.0");
  check::that(parse_quantity(" 4 ", Quantity::kForce, "--P") == 4.0,
              "parse_quantity(' 4 ', Quantity::kForce, '--P') == 4.0");

  check::throws<InputError>([&] { (void)(parse_quantity("2mpa", Quantity::kPressure, "--E")); },
                            {"--E", "unknown pressure unit 'mpa'", "Pa kPa MPa GPa"});
  check::throws<InputError>([&] { (void)(parse_quantity("2  MPa", Quantity::kPressure, "--E")); },
                            {"--E", "unit ' MPa'"});
  check::throws<InputError>([&] { (void)(parse_quantity("2um", Quantity::kPressure, "--E")); },
                            {"--E", "'um'"});
  check::throws<InputError>([&] { (void)(parse_quantity("2MPa", Quantity::kLength, "--R")); },
                            {"--R", "length unit"});
  check::throws<InputError>([&] { (void)(parse_quantity("2 UM", Quantity::kLength, "--R")); },
                            {"--R", "'UM'"});
  check::throws<InputError>([&] { (void)(parse_quantity("2MN", Quantity::kForce, "--P")); }, {"--P", "'MN'"});
  check::throws<InputError>([&] { (void)(parse_quantity("0", Quantity::kLength, "--R")); },
                            {"--R", "must be > 0"});
  check::throws<InputError>([&] { (void)(parse_quantity("-1um", Quantity::kLength, "--R")); },
                            {"--R", "'-1um' must be > 0"});
  check::throws<InputError>([&] { (void)(parse_quantity("", Quantity::kLength, "--R")); }, {"--R", "empty"});
  check::throws<InputError>([&] { (void)(parse_quantity("MPa", Quantity::kPressure, "--E")); },
                            {"--E", "not a number"});
  check::throws<InputError>([&] { (void)(parse_quantity("nan", Quantity::kPressure, "--E")); },
                            {"--E", "not a finite number"});
  check::throws<InputError>([&] { (void)(parse_quantity("inf MPa", Quantity::kPressure, "--E")); }, "--E");
  check::throws<InputError>([&] { (void)(parse_quantity("1e308GPa", Quantity::kPressure, "--E")); },
                            {"--E", "too large"});
  check::throws<InputError>([&] { (void)(parse_quantity("1e-320nm", Quantity::kLength, "--R")); },
                            {"--R", "too small"});
  check::throws<InputError>([&] { (void)(parse_quantity("1e999", Quantity::kLength, "--R")); },
                            {"--R", "outside the range"});
  check::throws<InputError>([&] { (void)(parse_quantity("0x1p3", Quantity::kLength, "--R")); }, "--R");
  check::throws<InputError>([&] { (void)(parse_quantity("2 MPa x", Quantity::kPressure, "--E")); }, "--E");
  check::throws<InputError>([&] { (void)(parse_quantity("1.2.3", Quantity::kLength, "--R")); },
                            {"--R", "not a number"});

  check::that(find_unit("um").has_value() && find_unit("um")->kind == Quantity::kLength,
              "find_unit('um').has_value() && find_unit('um')->kind == Quantity::kLength");
  check::that(find_unit("mN").has_value() && find_unit("mN")->to_si == 1e-3,
              "find_unit('mN').has_value() && find_unit('mN')->to_si == 1e-3");
  regression_unit_prefix_rounding();
  check::that(!find_unit("UM").has_value() && !find_unit("").has_value(),
              "!find_unit('UM').has_value() && !find_unit('').has_value()");
}

void test_parse_material() {
  const Material film = parse_material("2MPa,0.3", "--film");
  check::that(film.youngs_modulus == 2e6 && film.poisson_ratio == 0.3,
              "film.youngs_modulus == 2e6 && film.poisson_ratio == 0.3");
  const Material bare = parse_material("0.1,0.25", "--film");
  check::that(bare.youngs_modulus == 0.1 && bare.poisson_ratio == 0.25,
              "bare.youngs_modulus == 0.1 && bare.poisson_ratio == 0.25");
  const Material spaced = parse_material(" 2 MPa , 0.5 ", "--film");
  check::that(spaced.youngs_modulus == 2e6 && spaced.poisson_ratio == 0.5,
              "spaced.youngs_modulus == 2e6 && spaced.poisson_ratio == 0.5");
  check::that(parse_material("1,-0.99", "--film").poisson_ratio == -0.99,
              "parse_material('1,-0.99', '--film').poisson_ratio == -0.99");

  check::throws<InputError>([&] { (void)(parse_material("1,0.6", "--film")); },
                            "--film: Poisson ratio 0.6 is outside the allowed range (-1, 0.5]");
  check::throws<InputError>([&] { (void)(parse_material("1,-1", "--film")); },
                            {"--film", "Poisson ratio -1", "(-1, 0.5]"});
  check::throws<InputError>([&] { (void)(parse_material("1,nan", "--film")); },
                            {"--film", "Poisson ratio", "finite"});
  check::throws<InputError>([&] { (void)(parse_material("1,x", "--film")); },
                            {"--film", "Poisson ratio 'x'"});
  check::throws<InputError>([&] { (void)(parse_material("1,", "--film")); }, {"--film", "Poisson ratio"});
  check::throws<InputError>([&] { (void)(parse_material("0,0.3", "--film")); },
                            {"--film", "Young's modulus '0' must be > 0"});
  check::throws<InputError>([&] { (void)(parse_material("-2MPa,0.3", "--film")); },
                            {"--film", "Young's modulus"});
  check::throws<InputError>([&] { (void)(parse_material("2MPa", "--film")); }, {"--film", "E,nu"});
  check::throws<InputError>([&] { (void)(parse_material("1,0.3,4", "--film")); }, {"--film", "E,nu"});
  check::throws<InputError>([&] { (void)(parse_material("", "--film")); }, {"--film", "empty"});
  check::throws<InputError>([&] { (void)(parse_material("2um,0.3", "--film")); },
                            {"--film", "pressure unit 'um'"});
  check::throws<InputError>([&] { (void)(parse_material("1.7e308,0.5", "--film")); },
                            {"--film", "outside the allowed range"});
}

void test_parse_substrate() {
  check::that(parse_substrate("rigid", "--substrate").rigid, "parse_substrate('rigid', '--substrate').rigid");
  check::that(parse_substrate(" rigid ", "--substrate").rigid,
              "parse_substrate(' rigid ', '--substrate').rigid");
  const Substrate soft = parse_substrate("1GPa,0.25", "--substrate");
  check::that(!soft.rigid && soft.material.youngs_modulus == 1e9 && soft.material.poisson_ratio == 0.25,
              "!soft.rigid && soft.material.youngs_modulus == 1e9 && soft.material.poisson_ratio == 0.25");
  check::throws<InputError>([&] { (void)(parse_substrate("Rigid", "--substrate")); },
                            {"--substrate", "'Rigid'", "rigid"});
  check::throws<InputError>([&] { (void)(parse_substrate("", "--substrate")); }, {"--substrate", "empty"});
  check::throws<InputError>([&] { (void)(parse_substrate("1,0.7", "--substrate")); },
                            {"--substrate", "Poisson ratio 0.7"});
  check::throws<InputError>([&] { (void)(parse_substrate("rigid,0.3", "--substrate")); },
                            {"--substrate", "Young's modulus"});
}

void test_validate() {
  Material good;
  good.youngs_modulus = 2.0;
  good.poisson_ratio = 0.5;
  coatcontact::validate(good, "film");  // must not throw
  Material bad = good;
  bad.poisson_ratio = 0.51;
  check::throws<InputError>([&] { (void)(coatcontact::validate(bad, "film")); },
                            {"film", "Poisson ratio", "(-1, 0.5]"});
  bad = good;
  bad.youngs_modulus = std::nan("");
  check::throws<InputError>([&] { (void)(coatcontact::validate(bad, "film")); }, {"film", "Young's modulus"});
  bad.youngs_modulus = -1.0;
  check::throws<InputError>([&] { (void)(coatcontact::validate(bad, "film")); }, {"film", "Young's modulus"});
  Substrate substrate;
  substrate.rigid = true;
  substrate.material.youngs_modulus = -5.0;  // ignored when rigid
  coatcontact::validate(substrate);
  substrate.rigid = false;
  check::throws<InputError>([&] { (void)(coatcontact::validate(substrate)); },
                            {"substrate", "Young's modulus"});

  // E* = E/(1 - nu^2): film (1, 0) on substrate (10, 0.5) -> 1 / (10/0.75) = 0.075.
  Material film;
  film.youngs_modulus = 1.0;
  film.poisson_ratio = 0.0;
  Substrate elastic;
  elastic.material.youngs_modulus = 10.0;
  elastic.material.poisson_ratio = 0.5;
  check::close(coatcontact::Stack::film_on(film, elastic).modulus_ratio(), 0.075, tier::kRounding,
               "modulus_ratio E1*/E0*");
  elastic.rigid = true;
  check::that(coatcontact::Stack::film_on(film, elastic).modulus_ratio() == 0.0,
              "coatcontact::Stack::film_on(film, elastic).modulus_ratio() == 0.0");
}

}  // namespace

int main(int argc, char** argv) {
  // One argument: run only that regression test.
  if (argc == 2) {
    const std::string name = argv[1];
    if (name == "regression_list_decade_points_not_exact") {
      regression_list_decade_points_not_exact();
    } else if (name == "regression_unit_prefix_rounding") {
      regression_unit_prefix_rounding();
    } else {
      check::that(false, "unknown regression test '" + name + "'");
    }
    return check::exit_code();
  }
  test_parse_number();
  test_parse_list();
  test_parse_quantity();
  test_parse_material();
  test_parse_substrate();
  test_validate();
  return check::exit_code();
}
