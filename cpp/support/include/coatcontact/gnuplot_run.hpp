// The CLI's plots (fit --plot, afm fit --plot): gnuplot run on an embedded script with its
// input files in a private temporary folder. Private to the program, not installed.
#pragma once
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace coatcontact::cli {

// `text` as a gnuplot single-quoted string that enhanced text shows literally.
std::string gnuplot_string(const std::string& text);

// Writes `files` (name, contents) and `script` (as script_name) into a private temporary folder,
// then `settings(dir)` as settings.gp, and runs `gnuplot settings.gp script_name`. Returns the
// picture gnuplot writes to stdout (the caller writes it atomically); InputError naming --plot
// when the folder cannot be made or gnuplot fails. The folder is removed in every case.
// `option` names the option in the messages; with `warnings_fail`, a gnuplot warning line ("warning:", any case)
// on stderr (a picture gnuplot drew other than asked) is a NumericalError (exit 3) quoting it.
std::string run_gnuplot(const std::vector<std::pair<std::string, std::string>>& files, const std::string& script_name,
                        const std::string& script, const std::function<std::string(const std::string& dir)>& settings,
                        const std::string& option = "--plot", bool warnings_fail = false);

}  // namespace coatcontact::cli
