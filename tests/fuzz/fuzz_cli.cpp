// libFuzzer target: the command line, from argument parsing to pixels.
//
// The input is an argument list, NUL-separated ("--width\0 64\0-o\0a.png"),
// given to raycast::cli::parse_args as argv[1...]. Every accepted job's camera
// and sky are rendered small (width at most 64; at most 8 rows from each end
// of a taller image, in the image's own row coordinates) on every backend this
// CPU runs, in both precisions, with all, none and some of the kernels'
// shortcuts (render_options::shortcuts), to 32-bit float and to 8 bits, and checked:
//   - parse_args: exit code 0 or 2; a usage error is one line "raycast: error:
//     ..." on the error stream; an accepted job has a valid camera;
//   - float output is finite everywhere (no NaN, no infinity);
//   - --precision exact gives the same bits on every backend (src/kernels/README.md).
// AddressSanitizer and UndefinedBehaviorSanitizer catch the rest. Nothing here
// opens a file: the sinks are never called, and --help / --version print into
// a string.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "library/pipeline.h"
#include "options.h"
#include "render/render.h"

namespace {

using namespace raycast;

constexpr int64_t max_width = 64;
constexpr int64_t rows_per_end = 8;
constexpr size_t max_arguments = 64;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz_cli: %s\n", what.c_str());
  std::abort();
}

struct rendered {
  std::vector<unsigned char> bytes;
};

// Rows [r0, r1) of the scene with the given options, in format f.
rendered render_rows(const renderer& r, pixel_format f, int64_t r0, int64_t r1) {
  const size_t stride = size_t(r.cam().image_width) * bytes_per_pixel(f);
  rendered out;
  out.bytes.assign(stride * size_t(r1 - r0), 0xCD);
  r.render(image_band{out.bytes.data(), stride, f, r0, r1});
  return out;
}

void check_finite(const rendered& img, const std::string& where) {
  const size_t n = img.bytes.size() / sizeof(float);
  for (size_t k = 0; k < n; ++k) {
    float v;
    std::memcpy(&v, img.bytes.data() + k * sizeof(float), sizeof v);
    if (!std::isfinite(v))
      fail("non-finite value " + std::to_string(v) + " at float " + std::to_string(k) + " (" +
           where + ")");
  }
}

// `some_shortcuts`: a set of the plan's shortcuts picked by the input.
void render_everywhere(const cli::job& j, unsigned some_shortcuts) {
  scene s = make_scene(j.first.scene);
  s.cam.image_width = std::min(s.cam.image_width, max_width);
  const int64_t H = s.cam.image_height;
  // Row bands in the image's own coordinates, so v = j / (H - 1) is the real one.
  std::vector<std::pair<int64_t, int64_t>> bands;
  if (H <= 2 * rows_per_end) {
    bands.push_back({0, H});
  } else {
    bands.push_back({0, rows_per_end});
    bands.push_back({H - rows_per_end, H});
  }

  // The job's own options, as the CLI would run them (threads included).
  {
    const renderer r(s, renderer_options(j.options));
    for (const auto& [r0, r1] : bands) {
      check_finite(render_rows(r, pixel_format::rgb_f32, r0, r1), "the job's own options");
      (void)render_rows(r, pixel_format::rgb8, r0, r1);
    }
  }

  for (precision p : {precision::exact, precision::fast}) {
    for (unsigned shortcuts : {shortcut::all, shortcut::none, some_shortcuts}) {
      // Exact: the float paths (scalar and the SIMD kernels) must agree to the
      // bit; the reference renders in double and is not part of that promise.
      std::string base_name;
      std::vector<rendered> base_f32, base_u8;
      for (backend b : all_backends) {
        if (backend_unavailable(b)) continue;
        render_options o;
        o.which = b;
        o.prec = p;
        o.threads = 1;
        o.shortcuts = shortcuts;
        const renderer r(s, o);
        const std::string where = std::string(to_string(b)) + " " + std::string(to_string(p)) +
                                  " shortcuts=" + std::to_string(shortcuts);
        const bool compare = p == precision::exact && b != backend::reference;
        for (size_t k = 0; k < bands.size(); ++k) {
          const auto [r0, r1] = bands[k];
          rendered f32 = render_rows(r, pixel_format::rgb_f32, r0, r1);
          check_finite(f32, where);
          rendered u8 = render_rows(r, pixel_format::rgb8, r0, r1);
          if (!compare) continue;
          if (base_name.empty()) {
            base_f32.push_back(std::move(f32));
            base_u8.push_back(std::move(u8));
          } else if (f32.bytes != base_f32[k].bytes || u8.bytes != base_u8[k].bytes) {
            fail(where + " differs from " + base_name + " in rows " + std::to_string(r0) + ".." +
                 std::to_string(r1));
          }
        }
        if (compare && base_name.empty()) base_name = where;
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // NUL-separated arguments; a trailing piece without NUL is one too.
  std::vector<std::string> args{"raycast"};
  size_t start = 0;
  for (size_t k = 0; k <= size && args.size() <= max_arguments; ++k) {
    if (k == size || data[k] == 0) {
      if (k > start || k < size) args.emplace_back(reinterpret_cast<const char*>(data) + start, k - start);
      start = k + 1;
    }
  }
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);

  std::ostringstream out, err;
  const cli::parse_result parsed = cli::parse_args(int(args.size()), argv.data(), out, err);

  if (!parsed.run) {
    // 2: a usage error; 1: a scene file that cannot be read (an I/O failure).
    if (parsed.exit_code == 2 || parsed.exit_code == 1) {
      // One line, but for the line breaks of arguments the message quotes.
      const std::string e = err.str();
      long breaks_given = 0;
      for (size_t k = 1; k < args.size(); ++k)
        breaks_given += std::count(args[k].begin(), args[k].end(), '\n');
      if (e.rfind("raycast: error: ", 0) != 0 || e.back() != '\n' ||
          std::count(e.begin(), e.end(), '\n') > 1 + breaks_given)
        fail("an error must be one line 'raycast: error: ...', got: " + e);
    } else if (parsed.exit_code != 0) {
      fail("parse_args returned exit code " + std::to_string(parsed.exit_code));
    }
    return 0;
  }
  if (parsed.exit_code != 0) fail("a job came with exit code " + std::to_string(parsed.exit_code));
  if (!err.str().empty()) fail("an accepted job printed: " + err.str());
  const cli::job& j = *parsed.run;
  const camera c = make_camera(j.first.scene.cam);
  if (c.image_width < 1 || c.image_width > max_dimension || c.image_height < 1 ||
      c.image_height > max_dimension)
    fail("accepted a camera of " + std::to_string(c.image_width) + "x" +
         std::to_string(c.image_height));
  if (j.output.empty()) fail("accepted an empty output name");

  unsigned mix = 0;
  for (size_t k = 0; k < size; ++k) mix = mix * 31 + data[k];
  render_everywhere(j, (mix >> 7) & shortcut::all);
  return 0;
}
