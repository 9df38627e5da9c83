#include "aa_reference.h"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "cases.h"
#include "reference/reference.h"
#include "render/render.h"
#include "scene/builtin.h"

namespace raycast::bench {
namespace {

constexpr char magic[8] = {'R', 'C', 'A', 'A', 'R', 'E', 'F', '1'};
constexpr size_t name_bytes = 16;

// The header after the magic, field by field (no struct padding to agree on).
struct header {
  int64_t width = 0, height = 0;
  uint32_t samples = 0, sampler = 0;
  uint64_t seed = 0, fingerprint = 0;
  char scene[name_bytes] = {};
  double build_seconds = 0;
  uint32_t threads = 0, pad = 0;
};

template <class T>
void put(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
bool get(std::istream& in, T& v) {
  return bool(in.read(reinterpret_cast<char*>(&v), sizeof v));
}

void fnv(uint64_t& h, const void* data, size_t n) {
  const unsigned char* p = static_cast<const unsigned char*>(data);
  for (size_t k = 0; k < n; ++k) h = (h ^ p[k]) * 0x100000001b3ull;
}

// What the picture depends on besides the header's fields: the scene's
// one-sample picture (camera, sky, spheres, shading) and where the sampler
// puts the first pixel's samples.
uint64_t fingerprint(const scene& s, const sampling::sample_plan& plan) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (int64_t j = 0; j < s.cam.image_height; ++j)
    for (int64_t i = 0; i < s.cam.image_width; ++i) {
      const color c = reference_pixel(s, i, j);
      fnv(h, &c, sizeof c);
    }
  for (uint32_t k = 0; k < plan.count; ++k) {
    float xy[2];
    sampling::sample_offsets(plan, 0, 0, k, xy[0], xy[1]);
    fnv(h, xy, sizeof xy);
  }
  return h;
}

uint64_t fingerprint(const aa_reference_spec& spec) {
  const sampling::sample_table table(spec.sampler, spec.samples, spec.seed);
  return fingerprint(aa_scene(spec), table.plan());
}

}  // namespace

scene aa_scene(const aa_reference_spec& spec) {
  return raycast_test::make_scene(raycast_test::sized(spec.width, spec.height), {},
                                  builtin_spheres(spec.scene).value_or(std::vector<sphere>{}));
}

aa_reference compute_aa_reference(const aa_reference_spec& spec) {
  const auto start = std::chrono::steady_clock::now();
  const scene s = aa_scene(spec);
  const sampling::sample_table table(spec.sampler, spec.samples, spec.seed);
  aa_reference ref;
  ref.spec = spec;
  ref.fingerprint = fingerprint(s, table.plan());
  const int64_t W = spec.width, H = spec.height;
  ref.rgb.assign(size_t(W * H * 3), 0.0);
  int threads = 1;
#pragma omp parallel num_threads(available_cores())
  {
#pragma omp single
    threads = omp_get_num_threads();
#pragma omp for schedule(dynamic, 1)
    for (int64_t r = 0; r < H; ++r)
      for (int64_t i = 0; i < W; ++i) {
        const color c = reference_pixel_samples(s, table.plan(), i, H - 1 - r);
        double* px = &ref.rgb[size_t((r * W + i) * 3)];
        px[0] = c.r, px[1] = c.g, px[2] = c.b;
      }
  }
  ref.threads = threads;
  ref.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return ref;
}

std::string aa_reference_file(const std::string& dir, const aa_reference_spec& spec) {
  return dir + "/aa-ref-" + spec.scene + "-" + std::to_string(spec.width) + "x" +
         std::to_string(spec.height) + "-" + std::string(to_string(spec.sampler)) + "-" +
         std::to_string(spec.samples) + ".bin";
}

std::optional<aa_reference> load_aa_reference(const std::string& file, const aa_reference_spec& spec) {
  std::ifstream in(file, std::ios::binary);
  char m[sizeof magic];
  header h;
  if (!in || !get(in, m) || std::memcmp(m, magic, sizeof magic) != 0) return std::nullopt;
  if (!get(in, h.width) || !get(in, h.height) || !get(in, h.samples) || !get(in, h.sampler) ||
      !get(in, h.seed) || !get(in, h.fingerprint) || !get(in, h.scene) ||
      !get(in, h.build_seconds) || !get(in, h.threads) || !get(in, h.pad))
    return std::nullopt;
  if (h.width != spec.width || h.height != spec.height || h.samples != spec.samples ||
      h.sampler != uint32_t(spec.sampler) || h.seed != spec.seed ||
      std::string(h.scene, strnlen(h.scene, name_bytes)) != spec.scene ||
      h.fingerprint != fingerprint(spec))
    return std::nullopt;
  aa_reference ref;
  ref.spec = spec;
  ref.fingerprint = h.fingerprint;
  ref.build_seconds = h.build_seconds;
  ref.threads = int(h.threads);
  ref.from_cache = true;
  ref.file = file;
  ref.rgb.resize(size_t(spec.width * spec.height * 3));
  if (!in.read(reinterpret_cast<char*>(ref.rgb.data()), std::streamsize(ref.rgb.size() * sizeof(double))))
    return std::nullopt;
  if (in.peek() != std::char_traits<char>::eof()) return std::nullopt;  // longer than its header says
  return ref;
}

bool save_aa_reference(const std::string& file, const aa_reference& ref) {
  if (ref.spec.scene.size() > name_bytes) return false;
  header h;
  h.width = ref.spec.width;
  h.height = ref.spec.height;
  h.samples = ref.spec.samples;
  h.sampler = uint32_t(ref.spec.sampler);
  h.seed = ref.spec.seed;
  h.fingerprint = ref.fingerprint;
  std::memcpy(h.scene, ref.spec.scene.data(), ref.spec.scene.size());
  h.build_seconds = ref.build_seconds;
  h.threads = uint32_t(ref.threads);
  const std::string tmp = file + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(magic, sizeof magic);
    put(out, h.width), put(out, h.height), put(out, h.samples), put(out, h.sampler);
    put(out, h.seed), put(out, h.fingerprint), put(out, h.scene), put(out, h.build_seconds);
    put(out, h.threads), put(out, h.pad);
    out.write(reinterpret_cast<const char*>(ref.rgb.data()), std::streamsize(ref.rgb.size() * sizeof(double)));
    out.close();
    if (!out) {
      std::remove(tmp.c_str());
      return false;
    }
  }
  return std::rename(tmp.c_str(), file.c_str()) == 0;
}

aa_reference cached_aa_reference(const std::string& dir, const aa_reference_spec& spec) {
  if (dir.empty()) return compute_aa_reference(spec);
  const std::string file = aa_reference_file(dir, spec);
  if (auto ref = load_aa_reference(file, spec)) return std::move(*ref);
  aa_reference ref = compute_aa_reference(spec);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (save_aa_reference(file, ref)) ref.file = file;
  else std::fprintf(stderr, "raycast-bench: cannot write %s; the reference is not cached\n", file.c_str());
  return ref;
}

image_error measure_image_error(const float* image, const std::vector<double>& reference) {
  image_error e;
  double sum_sq = 0;
  for (size_t k = 0; k < reference.size(); ++k) {
    const double d = std::abs(double(image[k]) - reference[k]);
    sum_sq += d * d;
    if (!(d <= e.max_abs)) e.max_abs = std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
  }
  e.rmse = reference.empty() ? 0 : std::sqrt(sum_sq / double(reference.size()));
  return e;
}

}  // namespace raycast::bench
