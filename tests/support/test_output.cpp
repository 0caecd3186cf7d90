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
    CHECK(!exists(path));  // nothing at the target before commit
    CHECK(list_folder(folder).size() == 1);  // the temporary file
    out.commit();
    out.commit();  // a second commit is harmless
  }
  CHECK(read_all(path) == "# columns: a\n1\n");
  CHECK(list_folder(folder).size() == 1);  // only the target, no temp left
  struct stat info {};
  CHECK(stat(path.c_str(), &info) == 0 && (info.st_mode & 0044) != 0);  // not mkstemp's 0600 (umask 022 here)

  // Overwrite an existing file atomically.
  {
    Output out(path);
    out.stream() << "new\n";
    out.commit();
  }
  CHECK(read_all(path) == "new\n");
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
  CHECK(!exists(path));
  CHECK(list_folder(folder).empty());  // the temporary file was removed

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
  CHECK(read_all(path) == "old\n");
  CHECK(list_folder(folder).size() == 1);
  unlink(path.c_str());
}

void test_bad_paths(const std::string& folder) {
  const std::string missing = folder + "/no_such_folder/out.tsv";
  CHECK_THROWS(Output(missing), InputError, missing.c_str(), "does not exist");
  CHECK(!exists(folder + "/no_such_folder"));
  CHECK_THROWS(Output(folder + "/"), InputError, "folder");
  CHECK_THROWS(Output(folder), InputError, "is a folder");
  {
    std::ofstream(folder + "/plain") << "x";
  }
  CHECK_THROWS(Output(folder + "/plain/out.tsv"), InputError, "plain/out.tsv");
  unlink((folder + "/plain").c_str());
  if (geteuid() != 0) {  // root ignores permissions
    const std::string locked = folder + "/locked";
    mkdir(locked.c_str(), 0500);
    CHECK_THROWS(Output(locked + "/out.tsv"), InputError, "locked/out.tsv", "cannot create");
    rmdir(locked.c_str());
  }
  CHECK(list_folder(folder).empty());
}

// A child process writes without end and gets `signal_number`: neither the temporary file nor
// the target may remain, and the child must die of that signal (default action re-raised).
void test_signal_cleanup(const std::string& folder, int signal_number) {
  const std::string path = folder + "/interrupted.tsv";
  int ready[2];
  if (pipe(ready) != 0) {
    CHECK(false);
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
  CHECK(started);
  CHECK(list_folder(folder).size() == 1);  // the child's temporary file exists
  usleep(20000);
  kill(child, signal_number);
  int status = 0;
  waitpid(child, &status, 0);
  CHECK(WIFSIGNALED(status) && WTERMSIG(status) == signal_number);
  CHECK(!exists(path));
  CHECK(list_folder(folder).empty());
}

void test_stdout_output() {
  // Stdout is held in memory until commit() (issue 17: no partial output before a failure).
  Output out("");
  CHECK(&out.stream() != &std::cout);
  out.commit();
  Output dash("-");
  CHECK(&dash.stream() != &std::cout);
}

void test_format_value() {
  CHECK(format_value(0.1, "x") == "0.10000000000000001");
  CHECK(format_value(1.0, "x") == "1");
  CHECK(format_value(1e21, "x") == "1e+21");
  // Same text as the C library's "%.17g" (in the "C" locale of this test).
  for (double value : {-2.5e-300, 4.9e-324, 1.7976931348623157e308, 123456.789, -0.0, 1e-5}) {
    char expected[64];
    std::snprintf(expected, sizeof expected, "%.17g", value);
    CHECK(format_value(value, "x") == expected);
  }
  // %.17g round-trips every double.
  const double third = 1.0 / 3.0;
  CHECK(std::strtod(format_value(third, "x").c_str(), nullptr) == third);
  CHECK_THROWS(format_value(std::nan(""), "contact_radius"), NumericalError, "contact_radius", "not finite");
  CHECK_THROWS(format_value(std::numeric_limits<double>::infinity(), "load"), NumericalError, "load");
  CHECK_THROWS(format_value(-std::numeric_limits<double>::infinity(), "load"), NumericalError, "load");
}

void test_header_and_rows() {
  std::ostringstream out;
  write_header(out, {{"film", "1,0.3"}, {"note", "two\nlines"}}, {"q", "C"});
  write_row(out, {0.5, 2.0}, {"q", "C"});
  CHECK(out.str() == "# film: 1,0.3\n# note: two lines\n# columns: q\tC\n0.5\t2\n");
  std::ostringstream partial;
  CHECK_THROWS(write_row(partial, {1.0, std::nan("")}, {"q", "C"}), NumericalError, "'C'");
  CHECK(partial.str().empty());  // no half row
  CHECK_THROWS(write_row(partial, {1.0}, {"q", "C"}), std::logic_error, "1 values for 2 columns");
}

void test_run_guarded() {
  CHECK(run_guarded("test", [] { return 0; }) == 0);
  CHECK(run_guarded("test", []() -> int { throw InputError("--x: bad"); }) == 2);
  CHECK(run_guarded("test", []() -> int { throw NumericalError("no convergence"); }) == 3);
  CHECK(run_guarded("test", []() -> int { throw std::runtime_error("other"); }) == 3);
  CHECK(run_guarded("test", []() -> int { throw 42; }) == 3);
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
  return check::finish("test_support_output");
}
