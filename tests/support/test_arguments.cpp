// Unit tests of Arguments (option parsing) and usage().
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/cli_support.hpp"

using coatcontact::InputError;
using namespace coatcontact::cli;

namespace {

const std::vector<OptionSpec> kSpec = {
    {"--film", "E1,nu1", "film Young's modulus and Poisson ratio", true},
    {"--q", "LIST", "wavenumbers", false},
    {"--shift", "X", "a value that may be negative", false},
    {"--verbose", "", "more output", false},
};

Arguments parse(const std::vector<std::string>& args, std::size_t max_positionals = 0) {
  return Arguments(args, kSpec, max_positionals);
}

void test_values() {
  const Arguments a = parse({"--film", "1,0.3", "--q=1:10:3", "--verbose"});
  check::that(!a.help(), "!a.help()");
  check::that(a.has("--film") && a.has("--q") && a.has("--verbose") && !a.has("--shift"),
              "a.has('--film') && a.has('--q') && a.has('--verbose') && !a.has('--shift')");
  check::that(a.get("--film") == std::optional<std::string>("1,0.3"),
              "a.get('--film') == std::optional<std::string>('1,0.3')");
  check::that(a.get("--q") == std::optional<std::string>("1:10:3"),
              "a.get('--q') == std::optional<std::string>('1:10:3')");
  check::that(a.get("--verbose") == std::optional<std::string>(""),
              "a.get('--verbose') == std::optional<std::string>('')");
  check::that(!a.get("--shift").has_value(), "!a.get('--shift').has_value()");
  check::that(a.require("--film") == "1,0.3", "a.require('--film') == '1,0.3'");
  check::throws<InputError>([&] { (void)(a.require("--shift")); }, "--shift");
  check::that(a.positionals().empty(), "a.positionals().empty()");

  // A repeatable option (--layer, THEORY.md section 12) keeps every value in order.
  const std::vector<OptionSpec> layered = {{"--layer", "h,E,nu", "a layer", false, true}};
  const Arguments l({"--layer", "1,2,0.3", "--layer=2,1,0.45"}, layered);
  check::that(l.get_all("--layer") == std::vector<std::string>{"1,2,0.3", "2,1,0.45"} &&
                  l.get("--layer") == std::optional<std::string>("1,2,0.3"),
              "repeatable --layer keeps both values in order");
  check::that(a.get_all("--film") == std::vector<std::string>{"1,0.3"}, "get_all of a single option");

  // Negative numbers are values, also with '=' and with a leading '.'.
  const Arguments negative = parse({"--film", "1,0.3", "--shift", "-2.5", "--q", "-.5,1"});
  check::that(negative.get("--shift") == std::optional<std::string>("-2.5"),
              "negative.get('--shift') == std::optional<std::string>('-2.5')");
  check::that(negative.get("--q") == std::optional<std::string>("-.5,1"),
              "negative.get('--q') == std::optional<std::string>('-.5,1')");
  const Arguments equals = parse({"--film=1,0.3", "--shift=-1e3"});
  check::that(equals.get("--shift") == std::optional<std::string>("-1e3"),
              "equals.get('--shift') == std::optional<std::string>('-1e3')");
  // A value containing '=' after --name=.
  const Arguments eq_in_value = parse({"--film=a=b"});
  check::that(eq_in_value.get("--film") == std::optional<std::string>("a=b"),
              "eq_in_value.get('--film') == std::optional<std::string>('a=b')");
}

void test_errors() {
  check::throws<InputError>(
      [&] {
        (void)(parse({"--film", "1,0.3", "--foo"}));
      },
      "unknown option --foo (see --help)");
  check::throws<InputError>(
      [&] {
        (void)(parse({"--film", "1,0.3", "--foo=3"}));
      },
      "unknown option --foo (see --help)");
  check::throws<InputError>([&] { (void)(parse({"--film", "1,0.3", "-x"})); }, "unknown option -x");
  check::throws<InputError>([&] { (void)(parse({"--film"})); }, {"--film", "needs a value", "E1,nu1"});
  check::throws<InputError>([&] { (void)(parse({"--film", "--verbose"})); }, {"--film", "needs a value"});
  check::throws<InputError>([&] { (void)(parse({"--film", "-x"})); }, {"--film", "needs a value"});
  check::throws<InputError>([&] { (void)(parse({"--film="})); }, {"--film", "empty value"});
  check::throws<InputError>(
      [&] {
        (void)(parse({"--film", "1,0.3", "--film", "2,0.3"}));
      },
      {"--film", "more than once"});
  check::throws<InputError>(
      [&] {
        (void)(parse({"--film", "1,0.3", "--verbose=yes"}));
      },
      {"--verbose", "takes no value"});
  check::throws<InputError>([&] { (void)(parse({"--q", "1"})); }, "missing required option --film");
  check::throws<InputError>([&] { (void)(parse({})); }, "missing required option --film");
  check::throws<InputError>(
      [&] {
        (void)(parse({"--film", "1,0.3", "extra"}));
      },
      "unexpected argument 'extra'");
  check::throws<InputError>(
      [&] {
        (void)(parse({"--film", "1,0.3", "a", "b"}, 1));
      },
      {"unexpected argument 'b'", "at most 1"});
}

void test_help_and_positionals() {
  // --help wins over missing required options and over unknown options.
  check::that(parse({"--help"}).help(), "parse({'--help'}).help()");
  check::that(parse({"-h"}).help(), "parse({'-h'}).help()");
  check::that(parse({"--foo", "--help"}).help(), "parse({'--foo', '--help'}).help()");
  check::that(parse({"--q", "1", "-h"}).help(), "parse({'--q', '1', '-h'}).help()");

  const Arguments files = parse({"data.tsv", "--film", "1,0.3", "-5"}, 2);
  check::that(files.positionals().size() == 2 && files.positionals()[0] == "data.tsv" &&
                  files.positionals()[1] == "-5",
              "positionals 'data.tsv' and '-5'");
  // After "--" everything is positional, even option-looking text and --help.
  const Arguments ended = parse({"--film", "1,0.3", "--", "--help", "-x"}, 2);
  check::that(!ended.help() && ended.positionals().size() == 2 && ended.positionals()[0] == "--help",
              "!ended.help() && ended.positionals().size() == 2 && ended.positionals()[0] == '--help'");
  // "-" alone is positional (conventionally stdin/stdout).
  check::that(parse({"--film", "1,0.3", "-"}, 1).positionals().at(0) == "-",
              "parse({'--film', '1,0.3', '-'}, 1).positionals().at(0) == '-'");
}

void test_usage() {
  const std::string text = usage("kernel", "--film E1,nu1 [options]", "Computes the kernel.", kSpec);
  for (const char* fragment :
       {"usage: coatcontact kernel --film E1,nu1 [options]", "Computes the kernel.", "--film E1,nu1",
        "film Young's modulus and Poisson ratio (required)", "--verbose", "more output", "-h, --help"}) {
    check::that(text.find(fragment) != std::string::npos, std::string("usage shows '") + fragment + "'");
  }
  check::that(text.find("--verbose (required)") == std::string::npos,
              "text.find('--verbose (required)') == std::string::npos");
}

}  // namespace

int main() {
  test_values();
  test_errors();
  test_help_and_positionals();
  test_usage();
  return check::exit_code();
}
