// PartialLock, table_file_name and check_partial_rows (afm_partial.hpp).
#include "afm_partial.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "coatcontact/afm_batch_table.hpp"
#include "coatcontact/cli_support.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::cli {

PartialLock::PartialLock(const std::string& path, bool existed) {
  fd_ = ::open(path.c_str(), existed ? (O_RDWR | O_CLOEXEC) : (O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC), 0666);
  if (fd_ < 0) {
    if (!existed && errno == EEXIST) {
      throw InputError("--output: " + quoted(path) + " was just made by another run on the same FILE; let it finish, or continue it later with --resume");
    }
    throw InputError("--output: cannot open " + quoted(path) + " (" + std::strerror(errno) + ")");
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK) {
      throw InputError("--resume: " + quoted(path) + " is in use by another run on the same FILE (locked); let it finish or stop it first");
    }
    throw InputError("--output: cannot lock " + quoted(path) + " (" + std::strerror(error) + ")");
  }
}

PartialLock::~PartialLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

std::string table_file_name(const std::string& path) { return fit::afm_table_file_name(path); }

void check_partial_rows(const std::string& partial_path, const std::vector<std::pair<std::string, std::size_t>>& curves) {
  std::ifstream in(partial_path, std::ios::binary);
  std::string line;
  std::size_t file = 0, curve = 0, row = 0;
  bool header = true;
  while (std::getline(in, line)) {
    if (in.eof()) break;  // no line end: cut by a kill, dropped by the resume
    if (header && !line.empty() && line[0] == '#') continue;
    header = false;
    ++row;
    while (file < curves.size() && curve >= curves[file].second) ++file, curve = 0;
    const std::size_t tab = line.find('\t');
    const std::size_t tab2 = tab == std::string::npos ? std::string::npos : line.find('\t', tab + 1);
    const std::string name = line.substr(0, tab);
    const std::string index = tab2 == std::string::npos ? std::string() : line.substr(tab + 1, tab2 - tab - 1);
    if (file >= curves.size()) {
      throw InputError("--resume: row " + std::to_string(row) + " of " + quoted(partial_path) + " is one more than the run's " +
                       std::to_string(row - 1) + " curves (a duplicate or foreign row: two runs on one FILE?); remove the file");
    }
    if (name != curves[file].first || index != std::to_string(curve)) {
      throw InputError("--resume: row " + std::to_string(row) + " of " + quoted(partial_path) + " is curve " + quoted(index) + " of " +
                       quoted(name) + ", the run's curve " + std::to_string(row) + " is curve " + std::to_string(curve) + " of " +
                       quoted(curves[file].first) + " (a duplicate, missing or foreign row: two runs on one FILE?); remove the file");
    }
    ++curve;
  }
}

void check_partial_rows(const std::string& partial_path, const std::vector<std::string>& files,
                        const std::vector<fit::AfmFileSurvey>& survey) {
  std::vector<std::pair<std::string, std::size_t>> curves;
  for (std::size_t f = 0; f < files.size() && f < survey.size(); ++f) curves.emplace_back(table_file_name(files[f]), survey[f].curves);
  check_partial_rows(partial_path, curves);
}

}  // namespace coatcontact::cli
