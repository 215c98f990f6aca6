#include "gnuplot_run.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pcr::io_detail {
namespace {

namespace fs = std::filesystem;

/// 'text' for a POSIX shell: single quotes, an inner ' written as '\''.
std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// A fresh directory under the system's temporary directory (mkdtemp: unique, mode 0700).
std::string make_temporary_directory() {
  std::string pattern = (fs::temp_directory_path() / "pcr-figure-XXXXXX").string();
  if (!mkdtemp(pattern.data())) return "";
  return pattern;
}

std::string read_text(const fs::path& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace

std::string gnuplot_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

FigureOutcome run_gnuplot(const std::string& png_path, int width, int height,
                          const std::vector<GnuplotFile>& files, const std::string& script,
                          const std::string& gnuplot) {
  FigureOutcome outcome;
  if (std::system(("command -v " + shell_quote(gnuplot) + " > /dev/null 2>&1").c_str()) != 0) {
    outcome.message =
        "gnuplot is not installed (no '" + gnuplot + "' on PATH): install it (apt-get install gnuplot-nox)";
    return outcome;
  }
  const std::string directory = make_temporary_directory();
  if (directory.empty()) {
    outcome.message = "cannot create a temporary directory under " + fs::temp_directory_path().string();
    return outcome;
  }
  const fs::path dir(directory);
  for (const GnuplotFile& file : files) std::ofstream(dir / file.name) << file.text;
  const std::string absolute_png = fs::absolute(png_path).string();
  std::ofstream(dir / "figure.gp") << "set terminal pngcairo size " << width << "," << height
                                   << " noenhanced font 'Sans,11'\n"
                                   << "set output " << gnuplot_quote(absolute_png) << "\n"
                                   << script;
  std::error_code error;
  fs::remove(absolute_png, error);  // so that a stale picture never passes for a new one
  const fs::path log = dir / "gnuplot.log";
  const std::string command = "cd " + shell_quote(directory) + " && " + shell_quote(gnuplot) +
                              " figure.gp > " + shell_quote(log.string()) + " 2>&1";
  const int status = std::system(command.c_str());
  const bool written = fs::exists(absolute_png, error) && fs::file_size(absolute_png, error) > 0;
  if (status != 0 || !written) {
    outcome.message = "gnuplot failed (exit status " + std::to_string(status) + ") drawing '" + png_path +
                      "'; script and data kept in " + directory + ": " + read_text(log);
    return outcome;
  }
  fs::remove_all(dir, error);
  outcome.ok = true;
  return outcome;
}

}  // namespace pcr::io_detail
