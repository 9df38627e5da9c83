#include "run.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <cstdio>
#include <future>
#include <system_error>
#include <memory>
#include <utility>
#include <vector>

#include "io/io_error.h"
#include "io/movie.h"

namespace raycast::cli {
namespace {

using clock = std::chrono::steady_clock;
double seconds_since(clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); }

// The lesson's "Scanlines remaining" with a bar, the phase (rendering or
// writing a band) and the frame, shown only to a person at a terminal.
class progress {
 public:
  progress(bool enabled, size_t frames) : on_(enabled), frames_(frames) {}
  void frame(size_t i, int64_t rows) { i_ = i, rows_ = rows; }
  void show(int64_t rows_done, const char* phase) const {
    if (!on_) return;
    constexpr int width = 30;
    const int filled = int(width * rows_done / rows_);
    std::fprintf(stderr, "\r%sScanlines remaining: %lld [%.*s%*s] %3d%% %-9s", frame_text().c_str(),
                 static_cast<long long>(rows_ - rows_done), filled, "##############################", width - filled, "",
                 int(100 * rows_done / rows_), phase);
    std::fflush(stderr);
  }
  ~progress() {
    if (on_) std::fputs("\r\033[K", stderr);  // leave a clean line behind
  }

 private:
  std::string frame_text() const {
    return frames_ > 1 ? "frame " + std::to_string(i_ + 1) + "/" + std::to_string(frames_) + "  " : "";
  }
  bool on_;
  size_t frames_, i_ = 0;
  int64_t rows_ = 1;
};

bool exists(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0;
}

// One frame as a job: prepared, then written to its image or added to the movie.
void render_frame(const job& j, described_scene&& d, size_t k, const progress& bar, std::unique_ptr<io::movie_writer>& movie,
                  run_stats& st) {
  const auto t = clock::now();
  const api::job frame_job(std::move(d.scene), j.options);  // moves the spheres; freed once prepared
  st.prepare += seconds_since(t);
  st.load += d.load_seconds;
  st.job = frame_job.statistics();
  const auto show = [&bar](int64_t rows_done, const char* phase) { bar.show(rows_done, phase); };
  if (!j.movie) {
    const api::job::timings w = frame_job.write(output_name(j, k), j.options.format, show);
    st.output.open += w.open, st.output.render += w.render, st.output.write += w.write;
  } else {
    const auto r = clock::now();
    show(0, "rendering");
    const api::image img = frame_job.render(api::pixel_type::rgb8);
    st.output.render += seconds_since(r);
    const auto o = clock::now();
    if (!movie) movie = std::make_unique<io::movie_writer>(j.output, *j.movie, img.width, img.height, j.fps);
    st.output.open += seconds_since(o);
    const auto w = clock::now();
    show(img.height, "writing");
    movie->add_frame(img.data.data(), img.stride());
    st.output.write += seconds_since(w);
  }
  const api::job::stats after = frame_job.statistics();  // with what the render gathered
  st.job.light_lists = after.light_lists, st.job.list_seconds = after.list_seconds, st.job.list_bytes = after.list_bytes;
  st.rays += uint64_t(frame_job.width()) * uint64_t(frame_job.height()) * st.job.samples;
  ++st.frames;
}

}  // namespace

// The frames to render in turn: the job's list, or (every_frame) each frame
// the file has, found as the run goes; --skip-existing leaves out those
// whose image is there.
class frame_list {
 public:
  explicit frame_list(const job& j) : j_(j) {}
  // The index of the i-th frame to render after `after` (none: the first),
  // or nullopt at the end.
  std::optional<size_t> next(std::optional<size_t> after) const {
    size_t at = after ? position(*after) + 1 : 0;
    for (;; ++at) {
      std::optional<size_t> k;
      if (j_.every_frame) {
        if (j_.source->has_frame(at)) k = at;
      } else if (at < j_.frames.size()) {
        k = j_.frames[at];
      }
      if (!k || !j_.skip_existing || j_.movie || !exists(output_name(j_, *k))) return k;
    }
  }
  size_t size() const { return j_.every_frame ? 0 : j_.frames.size(); }  // 0: not known

 private:
  size_t position(size_t k) const {
    if (j_.every_frame) return k;
    return size_t(std::find(j_.frames.begin(), j_.frames.end(), k) - j_.frames.begin());
  }
  const job& j_;
};

void run(job& j, run_stats& st) {
  const frame_list frames(j);
  progress bar(!j.quiet && isatty(STDERR_FILENO), frames.size());
  if (!j.first.note.empty() && !j.quiet) std::fprintf(stderr, "raycast: note: %s\n", j.first.note.c_str());
  std::unique_ptr<io::movie_writer> movie;
  // Frame k described, with the next frame to render after it (read ahead
  // while k renders).
  using described = std::pair<std::optional<described_scene>, std::optional<size_t>>;
  const auto describe_after = [&j, &frames](std::optional<size_t> after) -> described {
    const std::optional<size_t> k = frames.next(after);
    if (!k) return {std::nullopt, std::nullopt};
    return {j.source->frame(*k), k};
  };
  std::optional<size_t> k = frames.next(std::nullopt);
  std::optional<described_scene> d;
  if (k) d = *k == j.frames[0] ? std::move(j.first) : j.source->frame(*k);
  const bool several = j.every_frame || j.frames.size() > 1;
  for (size_t i = 0; k; ++i) {
    // The next frame is read while this one renders, on a thread of its own
    // where one can start (else after it: a pids limit leaves one thread).
    std::future<described> ahead;
    try {
      ahead = std::async(several ? std::launch::async : std::launch::deferred, describe_after, k);
    } catch (const std::system_error&) {
      ahead = std::async(std::launch::deferred, describe_after, k);
    }
    bar.frame(i, std::max<int64_t>(1, j.region.height()));
    render_frame(j, std::move(*d), *k, bar, movie, st);
    described next = ahead.get();
    d = std::move(next.first);
    k = next.second;
  }
  if (movie) {
    const auto t = clock::now();
    movie->finish();
    st.output.write += seconds_since(t);
  }
}

void print_stats(const run_stats& st, double total) {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  const double rays_per_second = st.output.render > 0 ? double(st.rays) / st.output.render : 0.0;
  std::fprintf(stderr, "raycast stats:\n  load      %10.4f s\n  prepare   %10.4f s\n", st.load, st.prepare);
  // Where shadow or AO rays are cast: what their structures took of prepare.
  if (st.job.light_bytes > 0)
    std::fprintf(stderr, "  light     %10.4f s  (of prepare: %.1f MB for shadow and AO rays)\n", st.job.light_seconds,
                 double(st.job.light_bytes) / 1e6);
  std::fprintf(stderr,
               "  open      %10.4f s  (the output file, and the image library where its format needs it)\n"
               "  render    %10.4f s\n",
               st.output.open, st.output.render);
  if (st.job.light_bytes > 0)
    std::fprintf(stderr, "  lists     %10zu    (of render: the seen spheres' near-field lists, %.4f s, %.1f MB)\n",
                 st.job.light_lists, st.job.list_seconds, double(st.job.list_bytes) / 1e6);
  std::fprintf(stderr,
               "  write     %10.4f s\n"
               "  total     %10.4f s\n"
               "  rays/s    %10.4g  (%llu rays)\n"
               "  spheres   %10zu\n",
               st.output.write, total, rays_per_second,
               static_cast<unsigned long long>(st.rays), st.job.spheres);
  if (st.frames > 1) std::fprintf(stderr, "  frames    %10zu\n", st.frames);
  std::fprintf(stderr, "  peak RSS  %10.1f MB\n", double(ru.ru_maxrss) * 1024.0 / 1e6);
}

}  // namespace raycast::cli
