#pragma once
// Running gnuplot on a script and its data files in a fresh temporary directory (removed on success,
// kept and named in the message on failure); shared by the robot and the workspace pictures.
#include <string>
#include <vector>

#include "pcr/robots/io/gnuplot_figure.hpp"

namespace pcr::io_detail {

struct GnuplotFile {
  std::string name;  ///< file name inside the temporary directory
  std::string text;
};

/// 'text' for gnuplot: single-quoted strings take everything literally except '' for a quote.
std::string gnuplot_quote(const std::string& text);

/// Writes `files` and a script (pngcairo terminal of width x height pixels, output png_path, then
/// `script`) and runs `gnuplot` (looked up on PATH) in the temporary directory.
FigureOutcome run_gnuplot(const std::string& png_path, int width, int height,
                          const std::vector<GnuplotFile>& files, const std::string& script,
                          const std::string& gnuplot);

}  // namespace pcr::io_detail
