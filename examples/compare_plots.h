// `tessera compare --plots DIR`: the report drawn as PNG line plots by gnuplot (Debian
// gnuplot-nox, as `make bench-report` draws BENCHMARKS.md's): gnuplot gives labelled log axes
// and legible text for free, where drawing into a tessera Frame would need a font. It is
// needed only for --plots, and checked before the work.
//   time_vs_triangles.png  (with --sweep) frame and visibility times of both renderers against
//                          the triangle count, log-log, the crossover marked;
//   time_vs_resolution.png frame times against the pixel count of each --size (first thread count);
//   time_vs_threads.png    frame times against --threads (first size).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "examples/compare_report.h"

namespace tessera::cli {

// Throws tessera::Error when gnuplot is not on PATH or DIR cannot be created or written.
void check_plots(const std::filesystem::path& dir);

// Writes the plots (each atomically: a temporary, then renamed); returns their paths. Throws
// tessera::Error naming gnuplot's first complaint if it fails.
std::vector<std::string> write_plots(const std::filesystem::path& dir, const ComparisonReport& report);

}  // namespace tessera::cli
