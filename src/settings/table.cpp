#include "settings/table.h"

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/format.h"
#include "render/backend.h"
#include "render/render.h"
#include "scene/builtin.h"
#include "particles/colormap.h"
#include "scene/light.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace raycast {
namespace {

using enum setting_id;
using vt = value_type;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr value_range positive{0.0, inf, true, false};
constexpr value_range dimension{1.0, double(max_dimension)};
constexpr value_range color{-max_color, max_color};

constexpr std::string_view projection_names[] = {"perspective", "orthographic"};  // api::projection's order

// The scene's rows: also a scene file's camera, sky, light and
// ambient_occlusion keys.
void scene_rows(std::vector<setting>& t) {
  t.push_back({width, "--width", "-w", "camera.width", "width", vt::integer, dimension, {}, "N", "400",
               "Image width in pixels"});
  t.push_back({height, "--height", "", "camera.height", "height", vt::integer, dimension, {}, "N",
               "int(width / aspect), at least 1", "Image height in pixels"});
  t.push_back({aspect, "--aspect", "", "camera.aspect", "aspect", vt::aspect, positive, {}, "RATIO", "16:9",
               "Aspect ratio, W:H or a number"});
  t.push_back({vfov, "--vfov", "", "camera.vfov", "vfov", vt::real, {0.0, 180.0, true, true}, {}, "DEGREES", "",
               "Vertical field of view in degrees, instead of --viewport-height", 1});
  t.push_back({viewport_height, "--viewport-height", "", "camera.viewport_height", "viewport_height", vt::real,
               positive, {}, "H", "2.0", "Viewport height in world units", 1});
  t.push_back({focal_length, "--focal-length", "", "camera.focal_length", "focal_length", vt::real, positive, {},
               "F", "1.0", "Distance from the origin to the viewport"});
  t.push_back({projection, "--projection", "", "camera.projection", "projection", vt::name, {}, projection_names,
               "NAME", "perspective",
               "perspective (rays from the camera) or orthographic (parallel rays from an image plane through "
               "lookfrom, --viewport-height high)"});
  t.push_back({origin, "--origin", "", "", "", vt::triple, {}, {}, "X,Y,Z", "0,0,0", "Camera position", 2});
  t.push_back({lookfrom, "--lookfrom", "", "camera.lookfrom", "lookfrom", vt::triple, {}, {}, "X,Y,Z", "",
               "Camera position (the same point as --origin)", 2});
  t.push_back({lookat, "--lookat", "", "camera.lookat", "lookat", vt::triple, {}, {}, "X,Y,Z", "straight down -z",
               "Point the camera looks at"});
  t.push_back({vup, "--vup", "", "camera.vup", "vup", vt::triple, {}, {}, "X,Y,Z", "0,1,0",
               "Which way is up for the camera"});
  t.push_back({sky_bottom, "--sky-bottom", "", "sky.bottom", "sky_bottom", vt::triple, color, {}, "R,G,B", "1,1,1",
               "Colour looking straight down"});
  t.push_back({sky_top, "--sky-top", "", "sky.top", "sky_top", vt::triple, color, {}, "R,G,B", "0.5,0.7,1.0",
               "Colour looking straight up"});
  t.push_back({light, "--light", "", "light.direction", "light", vt::triple, {}, {}, "X,Y,Z", "a headlight",
               "Direction toward a directional light for lit spheres (instead of a light at the camera)"});
  t.push_back({shadows, "--shadows", "", "light.shadows", "shadows", vt::flag, {}, {}, "", "off",
               "Hard shadows: a ray from each lit hit toward the --light"});
  t.push_back({ao, "--ao", "", "ambient_occlusion.samples", "ao", vt::integer, {0.0, double(max_ao_samples)}, {},
               "N", "0", "Ambient occlusion: rays per lit hit, cosine-weighted about the normal (0: none)"});
  t.push_back({ao_distance, "--ao-distance", "", "ambient_occlusion.distance", "ao_distance", vt::real, positive, {},
               "D", "unbounded", "How far an ambient occlusion ray looks for a sphere"});
}

constexpr std::string_view shade_names[] = {"normal", "flat", "lit"};  // api::shading's order
constexpr std::string_view view_names[] = {"corner", "x", "y", "z"};

void particle_rows(std::vector<setting>& t) {
  t.push_back({radius, "--radius", "", "", "radius", vt::real, {0.0, max_sphere_extent, true, false}, {}, "R",
               "the file's radii, else the types'", "Every sphere's radius"});
  t.push_back({type_radius, "--type-radius", "", "", "type_radius", vt::type_map, {0.0, max_sphere_extent, true, false},
               {}, "T=R,...", "the element's van der Waals radius, else 0.5",
               "A particle type's radius: 1=0.5,2=0.35 (a type as the file names it: Cu, A, 1)"});
  t.push_back({type_color, "--type-color", "", "", "type_color", vt::type_map, {}, {}, "T=#RRGGBB,...",
               "the element's Jmol colour, else a palette", "A particle type's colour: 1=#1f77b4,2=#d62728"});
  t.push_back({color_by, "--color-by", "", "", "color_by", vt::text, {}, {}, "type|element|COLUMN",
               "the file's colours, else its types'", "Colour particles by type, element, or a column through --colormap"});
  t.push_back({colormap, "--colormap", "", "", "colormap", vt::name, {}, colormap_names, "NAME", "viridis",
               "The colours of --color-by COLUMN, low to high"});
  t.push_back({color_range, "--color-range", "", "", "color_range", vt::interval, {}, {}, "LO,HI",
               "the column's min and max",
               "The values --color-by maps to the colormap's ends (beyond them: the ends); pLO,pHI: percentiles, as p1,p99"});
  t.push_back({shade, "--shade", "", "", "shade", vt::name, {}, shade_names, "NAME",
               "lit where the particles have colours or types",
               "Every sphere's shading: lit (the light), normal (0.5 (N + 1)) or flat (its colour)"});
  t.push_back({view, "--view", "", "", "view", vt::name, {}, view_names, "NAME", "corner",
               "Where a particle file is seen from without a camera option: corner, or along x, y or z; the "
               "simulation box (else the particles' bounds) fills the picture"});
}

// Text the rows point at, kept for the program's life.
std::string_view keep(std::string s) {
  static std::vector<std::unique_ptr<std::string>> kept;
  kept.push_back(std::make_unique<std::string>(std::move(s)));
  return *kept.back();
}

void run_rows(std::vector<setting>& t) {
  static const std::vector<std::string_view> backends = [] {
    std::vector<std::string_view> n{to_string(raycast::backend::automatic)};
    for (raycast::backend b : all_backends) n.push_back(to_string(b));
    return n;
  }();
  static const std::vector<std::string_view> precisions = {to_string(raycast::precision::exact),
                                                           to_string(raycast::precision::fast)};
  static const std::vector<std::string_view> samplers = {
      to_string(sampler_kind::random), to_string(sampler_kind::stratified), to_string(sampler_kind::sobol)};
  t.push_back({output, "--output", "-o", "", "path", vt::text, {}, {}, "FILE", "",
               "Output file; '-' writes binary PPM to standard output"});
  t.push_back({scene, "--scene", "", "", "", vt::text, {}, {}, "NAME|FILE", "sky",
               keep("Built-in scene (" + builtin_scene_list() +
                    "), a .json scene file, whose settings the other options override, or a particle file: a LAMMPS dump, "
                    "extended XYZ, GSD or PLY file")});
  t.push_back({format, "--format", "", "", "format", vt::name, {}, io::format_name_list(), "FMT", "",
               "overrides the extension", 0, true});
  t.push_back({backend, "--backend", "", "", "backend", vt::name, {}, backends, "NAME", "auto: the best this CPU runs", ""});
  t.push_back({precision, "--precision", "", "", "precision", vt::name, {}, precisions, "MODE",
               to_string(default_precision), "fast: the sky's y / |d| from a reciprocal square root estimate (scenes without spheres)"});
  t.push_back({threads, "--threads", "", "", "threads", vt::integer, {0, 1024}, {}, "N", "0: all cores", "Render threads"});
  t.push_back({samples, "--samples", "", "", "samples", vt::integer, {1, double(max_samples)}, {}, "N", "1",
               "Samples per pixel, averaged (antialiasing); 1 is the pixel's own point"});
  t.push_back({sampler, "--sampler", "", "", "sampler", vt::name, {}, samplers, "NAME", to_string(default_sampler),
               "where a pixel's samples fall"});
  t.push_back({seed, "--seed", "", "", "seed", vt::seed, {}, {}, "N", "0",
               "Seed of the samples' random numbers, 0 to 2^64-1"});
  t.push_back({region, "--region", "", "", "region", vt::region, {}, {}, "X0,Y0,X1,Y1", "the whole image",
               "Render and write only the pixels x0 <= x < x1, y0 <= y < y1 of the image (y0 = 0 is the top row), the "
               "same bytes as those of the whole image"});
  t.push_back({frames, "--frames", "", "", "frame", vt::frames, {}, {}, "K|A:B[:S]", "every frame",
               "The frames of a trajectory to render: frame K, or a slice as Python's (-1: the last); -o takes a "
               "pattern such as f_%05d.png (the frame's index) or a movie (.mp4, .webm, .gif)"});
  t.push_back({fps, "--fps", "", "", "", vt::integer, {1, 1000}, {}, "N", "30", "A movie's frames per second"});
  t.push_back({skip_existing, "--skip-existing", "", "", "", vt::flag, {}, {}, "", "",
               "Render only the frames whose image is not there yet (a rerun after an interrupted run)"});
  t.push_back({quiet, "--quiet", "-q", "", "", vt::flag, {}, {}, "", "", "No progress on standard error"});
  t.push_back({stats, "--stats", "", "", "", vt::flag, {}, {}, "", "",
               "After the run, print on standard error the seconds each stage took (loading, the image library, "
               "preparing, rendering, writing), rays per second, spheres and peak memory"});
  t.push_back({version, "--version", "", "", "", vt::flag, {}, {}, "", "", "Print the version and the backend auto picks here"});
}

std::vector<setting> build() {
  std::vector<setting> t;
  scene_rows(t);
  particle_rows(t);
  run_rows(t);
  for (size_t k = 0; k < t.size(); ++k)
    if (size_t(t[k].id) != k) throw std::logic_error("the input table's rows are not in setting_id's order");
  return t;
}

}  // namespace

std::span<const setting> input_table() {
  static const std::vector<setting> table = build();
  return table;
}

const setting& input_row(setting_id id) { return input_table()[size_t(id)]; }

const setting* find_file_key(std::string_view file_key) {
  for (const setting& row : input_table())
    if (!row.file_key.empty() && row.file_key == file_key) return &row;
  return nullptr;
}

const setting* find_keyword(std::string_view keyword) {
  for (const setting& row : input_table())
    if (!row.keyword.empty() && row.keyword == keyword) return &row;
  return nullptr;
}

}  // namespace raycast
