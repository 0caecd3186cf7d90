// FILE.partial of `afm fit --output FILE` (the rows of a run, kept for --resume): one run at a
// time on it, and its rows checked against the run's curve list before a resume trusts them.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/afm_batch.hpp"

namespace coatcontact::cli {

// An exclusive flock(2) on FILE.partial for the life of the object. `existed`: the file was
// there when the run started (a resume); else it is created here (O_EXCL), so two runs never
// both start one. InputError naming the file when another run holds it (or just made it).
class PartialLock {
 public:
  PartialLock(const std::string& path, bool existed);
  ~PartialLock();
  PartialLock(const PartialLock&) = delete;
  PartialLock& operator=(const PartialLock&) = delete;

 private:
  int fd_ = -1;
};

// The file column of a table row: a name starting with '#' would make the row read as a
// comment, so it is written "./#..." (the same file).
std::string table_file_name(const std::string& path);

// Row i of FILE.partial (after its '#' header) must be curve i of the run: `curves` lists each
// file's name as the rows write it and its row count, in run order. A duplicate, missing or
// foreign row (two runs on one file, a hand edit) is an InputError naming the row and what
// was expected. A last line without its line end (a killed run) is not a row.
void check_partial_rows(const std::string& partial_path, const std::vector<std::pair<std::string, std::size_t>>& curves);
// The same for the run over `files` whose curve counts `survey` gives.
void check_partial_rows(const std::string& partial_path, const std::vector<std::string>& files,
                        const std::vector<fit::AfmFileSurvey>& survey);

}  // namespace coatcontact::cli
