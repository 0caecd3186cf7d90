// Unit tests of Output (atomic files, signal cleanup), format_value, write_header, write_row
// and run_guarded.
#include <dirent.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/cli_support.hpp"

using coatcontact::InputError;
using coatcontact::NumericalError;
using namespace coatcontact::cli;

namespace {

std::string make_temp_folder() {
  const char* base = std::getenv("TMPDIR");
  std::string pattern = std::string(base != nullptr && *base != '\0' ? base : "/tmp") + "/cc_output_test.XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) {
    std::perror("mkdtemp");
    std::exit(1);
  }
  return pattern;
}

std::vector<std::string> list_folder(const std::string& folder) {
  std::vector<std::string> names;
  DIR* dir = opendir(folder.c_str());
  if (dir == nullptr) return names;
  while (const dirent* entry = readdir(dir)) {
    const std::string name = entry->d_name;
    if (name != "." && name != "..") names.push_back(name);
  }
  closedir(dir);
  return names;
}

bool exists(const std::string& path) {
  struct stat info {};
  return stat(path.c_str(), &info) == 0;
}

std::string read_all(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void remove_folder(const std::string& folder) {
  for (const auto& name : list_folder(folder)) unlink((folder + "/" + name).c_str());
  rmdir(folder.c_str());
}

void test_commit_writes_file(const std::string& folder) {
  const std::string path = folder + "/result.tsv";
  {
    Output out(path);
    out.stream() << "# columns: a\n1\n";
    check::that(!exists(path), "!exists(path)");  // nothing at the target before commit
    check::that(list_folder(folder).size() == 1, "list_folder(folder).size() == 1");  // the temporary file
    out.commit();
    out.commit();  // a second commit is harmless
  }
  check::that(read_all(path) == "# columns: a\n1\n", "read_all(path) == '# columns: an1n'");
  check::that(list_folder(folder).size() == 1,
              "list_folder(folder).size() == 1");  // only the target, no temp left
  struct stat info {};
  check::that(
      stat(path.c_str(), &info) == 0 && (info.st_mode & 0044) != 0,
      "stat(path.c_str(), &info) == 0 && (info.st_mode & 0044) != 0");  // not mkstemp's 0600 (umask 022 here)

  // Overwrite an existing file atomically.
  {
    Output out(path);
    out.stream() << "new\n";
    out.commit();
  }
  check::that(read_all(path) == "new\n", "read_all(path) == 'newn'");
  unlink(path.c_str());
}

void test_no_commit_leaves_nothing(const std::string& folder) {
  const std::string path = folder + "/never.tsv";
  try {
    Output out(path);
    out.stream() << "partial data\n";
    throw NumericalError("solver failed");
  } catch (const NumericalError&) {
  }
  check::that(!exists(path), "!exists(path)");
  check::that(list_folder(folder).empty(), "list_folder(folder).empty()");  // the temporary file was removed

  // A failed run must not clobber an existing good file either.
  {
    std::ofstream(path) << "old\n";
  }
  try {
    Output out(path);
    out.stream() << "half";
    throw NumericalError("solver failed");
  } catch (const NumericalError&) {
  }
  check::that(read_all(path) == "old\n", "read_all(path) == 'oldn'");
  check::that(list_folder(folder).size() == 1, "list_folder(folder).size() == 1");
  unlink(path.c_str());
}

void test_bad_paths(const std::string& folder) {
  const std::string missing = folder + "/no_such_folder/out.tsv";
  check::throws<InputError>([&] { (void)(Output(missing)); }, {missing.c_str(), "does not exist"});
  check::that(!exists(folder + "/no_such_folder"), "!exists(folder + '/no_such_folder')");
  check::throws<InputError>([&] { (void)(Output(folder + "/")); }, "folder");
  check::throws<InputError>([&] { (void)(Output(folder)); }, "is a folder");
  {
    std::ofstream(folder + "/plain") << "x";
  }
  check::throws<InputError>([&] { (void)(Output(folder + "/plain/out.tsv")); }, "plain/out.tsv");
  unlink((folder + "/plain").c_str());
  if (geteuid() != 0) {  // root ignores permissions
    const std::string locked = folder + "/locked";
    mkdir(locked.c_str(), 0500);
    check::throws<InputError>([&] { (void)(Output(locked + "/out.tsv")); },
                              {"locked/out.tsv", "cannot create"});
    rmdir(locked.c_str());
  }
  check::that(list_folder(folder).empty(), "list_folder(folder).empty()");
}

// A child process writes without end and gets `signal_number`: neither the temporary file nor
// the target may remain, and the child must die of that signal (default action re-raised).
void test_signal_cleanup(const std::string& folder, int signal_number) {
  const std::string path = folder + "/interrupted.tsv";
  int ready[2];
  if (pipe(ready) != 0) {
    check::that(false, "false");
    return;
  }
  const pid_t child = fork();
  if (child == 0) {
    close(ready[0]);
    Output out(path);
    out.stream() << "first line\n";
    out.stream().flush();
    if (write(ready[1], "r", 1) != 1) _exit(10);
    for (;;) out.stream() << "1.2345678901234567\t2.5\t3.75\n";  // mid-write until killed
  }
  close(ready[1]);
  char byte = 0;
  const bool started = read(ready[0], &byte, 1) == 1;
  close(ready[0]);
  check::that(started, "started");
  check::that(list_folder(folder).size() == 1,
              "list_folder(folder).size() == 1");  // the child's temporary file exists
  usleep(20000);
  kill(child, signal_number);
  int status = 0;
  waitpid(child, &status, 0);
  check::that(WIFSIGNALED(status) && WTERMSIG(status) == signal_number,
              "WIFSIGNALED(status) && WTERMSIG(status) == signal_number");
  check::that(!exists(path), "!exists(path)");
  check::that(list_folder(folder).empty(), "list_folder(folder).empty()");
}

void test_stdout_output() {
  // Stdout is held in memory until commit() (issue 17: no partial output before a failure).
  Output out("");
  check::that(&out.stream() != &std::cout, "&out.stream() != &std::cout");
  out.commit();
  Output dash("-");
  check::that(&dash.stream() != &std::cout, "&dash.stream() != &std::cout");
}

void test_format_value() {
  check::that(format_value(0.1, "x") == "0.10000000000000001",
              "format_value(0.1, 'x') == '0.10000000000000001'");
  check::that(format_value(1.0, "x") == "1", "format_value(1.0, 'x') == '1'");
  check::that(format_value(1e21, "x") == "1e+21", "format_value(1e21, 'x') == '1e+21'");
  // Same text as the C library's "%.17g" (in the "C" locale of this test).
  for (double value : {-2.5e-300, 4.9e-324, 1.7976931348623157e308, 123456.789, -0.0, 1e-5}) {
    char expected[64];
    std::snprintf(expected, sizeof expected, "%.17g", value);
    check::that(format_value(value, "x") == expected, "format_value(value, 'x') == expected");
  }
  // %.17g round-trips every double.
  const double third = 1.0 / 3.0;
  check::that(std::strtod(format_value(third, "x").c_str(), nullptr) == third,
              "std::strtod(format_value(third, 'x').c_str(), nullptr) == third");
  check::throws<NumericalError>([&] { (void)(format_value(std::nan(""), "contact_radius")); },
                                {"contact_radius", "not finite"});
  check::throws<NumericalError>(
      [&] { (void)(format_value(std::numeric_limits<double>::infinity(), "load")); }, "load");
  check::throws<NumericalError>(
      [&] { (void)(format_value(-std::numeric_limits<double>::infinity(), "load")); }, "load");
}

void test_header_and_rows() {
  std::ostringstream out;
  write_header(out, {{"film", "1,0.3"}, {"note", "two\nlines"}}, {"q", "C"});
  write_row(out, {0.5, 2.0}, {"q", "C"});
  check::that(out.str() == "# film: 1,0.3\n# note: two lines\n# columns: q\tC\n0.5\t2\n",
              "out.str() == '# film: 1,0.3n# note: two linesn# columns: qtCn0.5t2n'");
  std::ostringstream partial;
  check::throws<NumericalError>([&] { (void)(write_row(partial, {1.0, std::nan("")}, {"q", "C"})); }, "'C'");
  check::that(partial.str().empty(), "partial.str().empty()");  // no half row
  check::throws<std::logic_error>(
      [&] {
        (void)(write_row(partial, {1.0}, {"q", "C"}));
      },
      "1 values for 2 columns");
}

void test_run_guarded() {
  check::that(run_guarded("test", [] { return 0; }) == 0, "run_guarded('test', [] { return 0; }) == 0");
  check::that(run_guarded("test", []() -> int { throw InputError("--x: bad"); }) == 2,
              "run_guarded('test', []() -> int { throw InputError('--x: bad'); }) == 2");
  check::that(run_guarded("test", []() -> int { throw NumericalError("no convergence"); }) == 3,
              "run_guarded('test', []() -> int { throw NumericalError('no convergence'); }) == 3");
  check::that(run_guarded("test", []() -> int { throw std::runtime_error("other"); }) == 3,
              "run_guarded('test', []() -> int { throw std::runtime_error('other'); }) == 3");
  check::that(run_guarded("test", []() -> int { throw 42; }) == 3,
              "run_guarded('test', []() -> int { throw 42; }) == 3");
}

}  // namespace

int main() {
  umask(022);
  // A shell starting this test in the background may have set SIGINT to "ignore", and Output
  // respects an ignored signal; the signal tests need the default dispositions.
  signal(SIGINT, SIG_DFL);
  signal(SIGTERM, SIG_DFL);
  const std::string folder = make_temp_folder();
  test_commit_writes_file(folder);
  test_no_commit_leaves_nothing(folder);
  test_bad_paths(folder);
  test_signal_cleanup(folder, SIGTERM);
  test_signal_cleanup(folder, SIGINT);
  test_stdout_output();
  test_format_value();
  test_header_and_rows();
  test_run_guarded();
  remove_folder(folder);
  return check::exit_code();
}
