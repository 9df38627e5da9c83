// What the bench prints: counters that need other rows' times (filled in a
// reporter wrapper), the error-vs-run-time summary, its SVG plot, and the
// stiff-case tables.
#pragma once
#include <benchmark/benchmark.h>

#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "errors.h"
#include "sphere_numerics.h"

namespace raycast::bench {

// A row name split into its parts: render/BACKEND/PRECISION/WxH/tTHREADS/OUT
// (the sky), render/BACKEND/PRECISION/SCENE/WxH/tTHREADS/OUT (a scene with
// spheres; kind "scene"), aa/BACKEND[/SAMPLER]/SCENE/WxH/sSAMPLES (antialiased,
// SAMPLES rays a pixel; kind "aa"; the book's peer has no SAMPLER part) or
// bound/memset/WxH/rgb8.
struct row_name {
  std::string kind, backend, precision, out;
  std::string scene;  // scene rows only
  int64_t width = 0, height = 0;
  int threads = 1;
  std::string shortcuts;  // shortcuts/ rows: which shortcuts the plan may take
  int64_t samples = 1;    // aa/ rows: rays a pixel
  std::string sampler;    // aa/ rows of ours: random, stratified or sobol
};
std::optional<row_name> parse_row_name(const std::string& name);
std::string render_row_name(const std::string& backend, std::string_view precision, int64_t w,
                            int64_t h, int threads, std::string_view out);
std::string memset_row_name(int64_t w, int64_t h);
// sampler empty: aa/BACKEND/SCENE/WxH/sSAMPLES (the book's peer).
std::string aa_row_name(const std::string& backend, const std::string& sampler, const std::string& scene,
                        int64_t w, int64_t h, int64_t samples);
std::string scene_row_name(const std::string& backend, std::string_view precision,
                           const std::string& scene, int64_t w, int64_t h, int threads,
                           std::string_view out);
// shortcuts/BACKEND/PRECISION/WxH/t1/rgb8/SET: the kernel allowed only some of
// the plan's shortcuts (render_options::shortcuts; none, one, or all).
std::string shortcuts_row_name(const std::string& backend, std::string_view precision, int64_t w,
                               int64_t h, std::string_view set);

// One measured render row, for the summary: the median time per iteration
// over its repetitions (--benchmark_repetitions) and the counters its
// benchmark set.
struct measured_row {
  row_name name;
  double seconds = 0;
  std::map<std::string, double> counters;
  bool from_iterations = false;
};

// Times of every row reported so far, shared by the display and file reporters.
class run_table {
 public:
  // Adds ns_per_px, Mpix_per_s, speedup and vs_memset (aa/ rows:
  // ns_per_sample) to the runs of one benchmark and records them.
  void fill(std::vector<benchmark::BenchmarkReporter::Run>& runs);
  const std::map<std::string, measured_row>& rows() const { return rows_; }
  std::optional<double> seconds(const std::string& name) const;
  // The median over a row's repetitions of a counter its benchmark set.
  std::optional<double> counter(const std::string& row, const std::string& name) const;
  const std::map<std::string, double>& all_seconds() const { return seconds_; }

 private:
  std::map<std::string, double> seconds_;  // "name|aggregate" -> seconds per iteration
  std::map<std::string, double> counters_;  // "name|counter" -> median
  std::map<std::string, measured_row> rows_;
};

// Forwards every call to another reporter, the counters filled in first.
class counter_filler : public benchmark::BenchmarkReporter {
 public:
  counter_filler(benchmark::BenchmarkReporter* inner, run_table& table)
      : inner_(inner), table_(table) {}
  bool ReportContext(const Context& context) override;
  void ReportRuns(const std::vector<Run>& runs) override;
  void Finalize() override;

 private:
  benchmark::BenchmarkReporter* inner_;
  run_table& table_;
};

struct summary_options {
  int64_t width = 3840, height = 2160;
  int threads = 1;
  std::string out = "rgb8";
  std::string cpu, date;
};

struct summary_row {
  std::string label;  // backend/precision, or backend/precision/scene
  std::string scene;  // empty for the sky
  double ns_per_px = 0;
  std::optional<double> speedup;
  double max_abs_err = 0, lsb_mismatch = 0;
  int max_lsb = 0;
  bool pareto = false;
};

// The rows at the summary's size, threads and output (the sky's, then each
// sphere scene's), sorted by time within each, with the Pareto-optimal ones
// (no other row of the same scene both faster and at most as wrong in
// max_abs_err) marked. max_abs_err is NaN for a row without float output.
std::vector<summary_row> summary_rows(const run_table& table, const summary_options& opt);
void print_summary(std::ostream& os, const std::vector<summary_row>& rows,
                   const summary_options& opt, const std::vector<skipped_backend>& skipped);
// A log-log chart's frame: the page, the plot area, its decades and titles.
struct log_chart {
  double W = 960, H = 640, left = 90, right = 150, top = 80, bottom = 70;
  int x0 = 0, x1 = 1, y0 = 0, y1 = 1;  // decades shown
  double y_floor = 0;                  // values below it are drawn at it
  bool zero_at_bottom = false;         // label the lowest decade "0"
  std::string x_title, y_title;
  double pw() const { return W - left - right; }
  double ph() const { return H - top - bottom; }
  double px(double v) const;  // page coordinates of a value
  double py(double v) const;  // (infinite: the top)
  void fit_x(double lo, double hi);  // the decades covering [lo, hi]
  void fit_y(double lo, double hi);  // ...and the floor at lo
};
// The <svg> element, a white page, the title and subtitle (already escaped),
// the grid, the decades' labels and the axis titles.
void write_svg_header(std::ostream& out, const log_chart& c, const std::string& title,
                      const std::string& subtitle);

// Log-log scatter of ns/px against max_abs_err; false when the file cannot be written.
bool write_svg(const std::string& file, const std::vector<summary_row>& rows,
               const summary_options& opt);

struct stiff_result {
  std::string name;
  int64_t width = 0, height = 0;
  std::string invalid;              // validate()'s message when the camera is refused
  std::vector<error_stats> errors;  // per path
};
// What each shortcut saves: ns/px of the shortcuts/ rows, none first.
void print_shortcuts(std::ostream& os, const run_table& table, const std::vector<std::string>& sets);

void print_stiff(std::ostream& os, const std::vector<path>& paths,
                 const std::vector<stiff_result>& results);

// One stiff sphere case (tests/support/sphere_numerics.h) against the double
// reference: ours (the scalar renderer, exact mode: every backend's bits), the
// book's ch. 6 formula in float, and Embree (rtcIntersect1).
struct sphere_stiff_result {
  std::string name;
  int64_t width = 0, height = 0;
  raycast_test::sphere_metrics ours, naive, embree;
  std::string embree_error;  // Embree's message when it could not build the scene
};
// A Markdown table (README "Numerics"), each cell "ours / naive / Embree".
void print_sphere_stiff(std::ostream& os, const std::vector<sphere_stiff_result>& results);

std::string cpu_model();
std::string today();

// Text helpers the report rooms share: printf into a string, "WxH", an error
// as "%.1e" (0 and inf spelled out), XML escaping, and an SVG "10^e" label.
__attribute__((format(printf, 1, 2))) std::string strf(const char* format, ...);
std::string size_text(int64_t w, int64_t h);
std::string error_text(double e);
std::string xml_escape(const std::string& s);
std::string decade_label(int e);

}  // namespace raycast::bench
