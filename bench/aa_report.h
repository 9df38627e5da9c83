// The antialiasing rows' summary (bench/aa_rows.h): per scene a table of
// sampler x N with ns/px, ns/sample, RMSE and max error against the converged
// reference; each sampler's log-log slope of RMSE against N; the samples each
// sampler needs to match the book's RMSE at 100 samples; the per-sample speed
// of ours against the book's; and a log-log chart of RMSE against ns/px.
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

#include "aa_rows.h"
#include "report.h"

namespace raycast::bench {

void print_aa_summary(std::ostream& os, const run_table& table, const aa_config& cfg,
                      const std::vector<const aa_reference*>& refs, const std::string& cpu,
                      const std::string& date);

// The chart's file next to --plot's: FILE.svg -> FILE-aa.svg.
std::string aa_plot_file(const std::string& plot);
// false when there is nothing to plot or the file cannot be written.
bool write_aa_svg(const std::string& file, const run_table& table, const aa_config& cfg,
                  const std::string& cpu, const std::string& date);

}  // namespace raycast::bench
