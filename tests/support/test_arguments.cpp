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
  CHECK(!a.help());
  CHECK(a.has("--film") && a.has("--q") && a.has("--verbose") && !a.has("--shift"));
  CHECK(a.get("--film") == std::optional<std::string>("1,0.3"));
  CHECK(a.get("--q") == std::optional<std::string>("1:10:3"));
  CHECK(a.get("--verbose") == std::optional<std::string>(""));
  CHECK(!a.get("--shift").has_value());
  CHECK(a.require("--film") == "1,0.3");
  CHECK_THROWS(a.require("--shift"), InputError, "--shift");
  CHECK(a.positionals().empty());

  // Negative numbers are values, also with '=' and with a leading '.'.
  const Arguments negative = parse({"--film", "1,0.3", "--shift", "-2.5", "--q", "-.5,1"});
  CHECK(negative.get("--shift") == std::optional<std::string>("-2.5"));
  CHECK(negative.get("--q") == std::optional<std::string>("-.5,1"));
  const Arguments equals = parse({"--film=1,0.3", "--shift=-1e3"});
  CHECK(equals.get("--shift") == std::optional<std::string>("-1e3"));
  // A value containing '=' after --name=.
  const Arguments eq_in_value = parse({"--film=a=b"});
  CHECK(eq_in_value.get("--film") == std::optional<std::string>("a=b"));
}

void test_errors() {
  CHECK_THROWS(parse({"--film", "1,0.3", "--foo"}), InputError, "unknown option --foo (see --help)");
  CHECK_THROWS(parse({"--film", "1,0.3", "--foo=3"}), InputError, "unknown option --foo (see --help)");
  CHECK_THROWS(parse({"--film", "1,0.3", "-x"}), InputError, "unknown option -x");
  CHECK_THROWS(parse({"--film"}), InputError, "--film", "needs a value", "E1,nu1");
  CHECK_THROWS(parse({"--film", "--verbose"}), InputError, "--film", "needs a value");
  CHECK_THROWS(parse({"--film", "-x"}), InputError, "--film", "needs a value");
  CHECK_THROWS(parse({"--film="}), InputError, "--film", "empty value");
  CHECK_THROWS(parse({"--film", "1,0.3", "--film", "2,0.3"}), InputError, "--film", "more than once");
  CHECK_THROWS(parse({"--film", "1,0.3", "--verbose=yes"}), InputError, "--verbose", "takes no value");
  CHECK_THROWS(parse({"--q", "1"}), InputError, "missing required option --film");
  CHECK_THROWS(parse({}), InputError, "missing required option --film");
  CHECK_THROWS(parse({"--film", "1,0.3", "extra"}), InputError, "unexpected argument 'extra'");
  CHECK_THROWS(parse({"--film", "1,0.3", "a", "b"}, 1), InputError, "unexpected argument 'b'", "at most 1");
}

void test_help_and_positionals() {
  // --help wins over missing required options and over unknown options.
  CHECK(parse({"--help"}).help());
  CHECK(parse({"-h"}).help());
  CHECK(parse({"--foo", "--help"}).help());
  CHECK(parse({"--q", "1", "-h"}).help());

  const Arguments files = parse({"data.tsv", "--film", "1,0.3", "-5"}, 2);
  CHECK(files.positionals().size() == 2 && files.positionals()[0] == "data.tsv" &&
        files.positionals()[1] == "-5");
  // After "--" everything is positional, even option-looking text and --help.
  const Arguments ended = parse({"--film", "1,0.3", "--", "--help", "-x"}, 2);
  CHECK(!ended.help() && ended.positionals().size() == 2 && ended.positionals()[0] == "--help");
  // "-" alone is positional (conventionally stdin/stdout).
  CHECK(parse({"--film", "1,0.3", "-"}, 1).positionals().at(0) == "-");
}

void test_usage() {
  const std::string text = usage("kernel", "--film E1,nu1 [options]", "Computes the kernel.", kSpec);
  std::string missing;
  CHECK(check::contains_all(text,
                            {"usage: coatcontact kernel --film E1,nu1 [options]", "Computes the kernel.",
                             "--film E1,nu1", "film Young's modulus and Poisson ratio (required)",
                             "--verbose", "more output", "-h, --help"},
                            missing));
  CHECK(text.find("--verbose (required)") == std::string::npos);
}

}  // namespace

int main() {
  test_values();
  test_errors();
  test_help_and_positionals();
  test_usage();
  return check::finish("test_support_arguments");
}
