// gnuplot for the CLI's plots (coatcontact/gnuplot_run.hpp).
#include "coatcontact/gnuplot_run.hpp"

#include <stdlib.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "coatcontact/errors.hpp"

namespace coatcontact::cli {

std::string gnuplot_string(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') {
      out += "''";
    } else if (c == '_' || c == '@' || c == '&' || c == '~' || c == '{' || c == '}') {
      out += '\\';  // escaped: enhanced text would read them as markup (^ is kept for the units)
      out += c;
    } else if (static_cast<unsigned char>(c) >= 32) {
      out += c;
    }
  }
  return out + "'";
}

std::string run_gnuplot(const std::vector<std::pair<std::string, std::string>>& files, const std::string& script_name,
                        const std::string& script, const std::function<std::string(const std::string& dir)>& settings,
                        const std::string& option, bool warnings_fail) {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/coatcontact-plot.XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (mkdtemp(buffer.data()) == nullptr) throw InputError(option + ": cannot create a temporary folder for gnuplot");
  const std::string dir(buffer.data());
  struct Cleanup {
    std::string dir;
    ~Cleanup() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  } cleanup{dir};
  const auto save = [&](const std::string& name, const std::string& text) {
    std::ofstream file(dir + "/" + name, std::ios::binary);
    file << text;
    if (!file) throw InputError(option + ": cannot write the temporary file " + dir + "/" + name);
  };
  for (const auto& [name, text] : files) save(name, text);
  save(script_name, script);
  save("settings.gp", settings(dir) + "\n");
  const std::string command = "gnuplot '" + dir + "/settings.gp' '" + dir + "/" + script_name + "' 2>'" + dir + "/err'";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) throw InputError(option + ": cannot run gnuplot");
  std::string picture;
  char chunk[65536];
  std::size_t got;
  while ((got = std::fread(chunk, 1, sizeof chunk, pipe)) > 0) picture.append(chunk, got);
  const int status = pclose(pipe);
  if (status != 0 || picture.empty()) {
    std::ifstream err(dir + "/err");
    std::string first;
    std::getline(err, first);
    throw InputError(option + ": gnuplot failed" +
                     (first.empty() ? std::string(" (is gnuplot with the cairo terminals installed?)") : ": " + first));
  }
  if (warnings_fail) {
    std::ifstream err(dir + "/err");
    for (std::string line; std::getline(err, line);) {
      std::string lower = line;  // gnuplot writes both "warning:" and "Warning:"
      for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (lower.find("warning:") != std::string::npos) throw NumericalError(option + ": gnuplot warned: " + line);
    }
  }
  return picture;
}

}  // namespace coatcontact::cli
