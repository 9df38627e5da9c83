#include "library/source.h"

#include <algorithm>
#include <chrono>
#include <utility>
#include <variant>

#include "formats/registry.h"
#include "particles/framing.h"
#include "particles/spheres.h"
#include "scene/builtin.h"
#include "scene/scene.h"
#include "text/names.h"

namespace raycast {
namespace {

using enum setting_id;
using kind = error_kind;
using steady = std::chrono::steady_clock;

double seconds_since(steady::time_point t) { return std::chrono::duration<double>(steady::now() - t).count(); }

// The file's keys (or a particle file's framing) with the front end's
// settings over them, resolved and checked.
described_scene finish(scene_file_contents&& c, const std::string& file, const settings& over, front_end fe) {
  settings merged = std::move(c.keys);
  merge(merged, over);
  if (auto e = resolve_scene(merged, c.scene)) {
    const bool from_file = e->row && merged.has(e->row->id) && !merged[e->row->id]->where.empty();
    throw refusal{kind::invalid_argument, e->source, from_file ? file : "", e->message};
  }
  // What one value cannot say (lookat = lookfrom, vup along the view, a
  // derived height, spheres far from the camera) is the scene's to check,
  // once; here only the field it blames becomes the setting that set it.
  if (auto e = validate(c.scene)) {
    const blamed b = blame(*e, merged, !file.empty());
    if (b.from_file) throw refusal{kind::invalid_argument, path(*e), file, e->message};
    const std::string source = merged.has(b.id)              ? merged[b.id]->source
                               : fe == front_end::library ? path(*e)
                                                          : spell(input_row(b.id), fe);
    throw refusal{kind::invalid_argument, source, "", e->message};
  }
  return {std::move(c.scene), file, 0.0, ""};
}

refusal read_refusal(const scene_file_error& e, std::string file) {
  return refusal{e.io ? kind::io : kind::invalid_argument, e.path, std::move(file), e.message};
}

// --radius and --shade over every sphere of a scene that is not particle data.
void shape_spheres(std::vector<sphere>& spheres, const api::particles& p) {
  for (sphere& s : spheres) {
    if (p.radius) s.radius = *p.radius;
    if (p.shade) s.shade = *p.shade;
  }
}

// A particle option the frame refuses, named as the front end spells it
// where the user gave it; else the file is to blame.
refusal particle_refused(const particle_refusal& e, const settings& over, const std::string& file) {
  const setting* row = find_keyword(e.keyword);
  if (row && over.has(row->id)) return refusal{kind::invalid_argument, over[row->id]->source, file, e.what()};
  return refusal{kind::invalid_argument, "", file, e.what()};
}

double largest_radius(const api::sphere_arrays& a) {
  double r = 0;
  const size_t n = a.radii.stride == 0 ? std::min<size_t>(a.count, 1) : a.count;
  for (size_t k = 0; k < n; ++k) r = std::max(r, a.radii.get(k));
  return r;
}

// The camera settings framing frame f (particles/framing.h), as a layer the
// front end's settings merge over where they place no camera (no lookfrom
// or lookat): a vup given wins, and the fit takes the projection, field of
// view and aspect given.
settings framing_layer(const particle_frame& f, const api::sphere_arrays& a, const settings& over_,
                       const api::particles& particles_, const std::string& file_) {
  api::scene asked;
  resolve_scene(over_, asked);  // a refusal here is reported by finish()
  const api::camera& g = asked.cam;
  const bool ortho = g.projection == api::projection::orthographic;
  double vfov = framing_vfov;
  if (g.vfov) vfov = *g.vfov;
  else if (over_.has(viewport_height) || over_.has(focal_length))
    vfov = 2.0 * std::atan(g.viewport_height / (2.0 * g.focal_length)) * 180.0 / 3.14159265358979323846;
  const framed_camera c = frame_camera(f, largest_radius(a), particles_.view, g.projection, vfov, g.aspect);
  settings s;
  const auto set = [&](setting_id id) -> value& {
    given& v = s[id].emplace();
    v.source = std::string(input_row(id).file_key);
    v.where = file_.empty() ? " (the camera framing the particles)" : " (the camera framing " + file_ + ")";
    return v.v;
  };
  const auto triple = [&](setting_id id, const api::vec3& x) { set(id).triple = {x.x, x.y, x.z}; };
  triple(lookfrom, c.lookfrom);
  triple(lookat, c.lookat);
  triple(vup, c.vup);
  if (ortho) set(viewport_height).real = c.viewport_height;
  else set(setting_id::vfov).real = c.vfov;
  return s;
}

// Whether the front end's settings place the camera (then no framing).
bool placed(const settings& over) { return over.has(lookfrom) || over.has(origin) || over.has(lookat); }

}  // namespace

scene_source::scene_source(const std::optional<std::string>& scene, settings over, front_end fe)
    : fe_(fe), over_(std::move(over)) {
  if (!scene) {
    whole_.emplace();
  } else if (auto spheres = builtin_spheres(*scene)) {
    whole_.emplace();
    whole_->scene.spheres = std::move(*spheres);
  } else if (formats::names_a_file(*scene)) {
    open_file(*scene);
  } else {
    throw refusal{kind::invalid_argument, "", "",
                  not_one_of(*scene, quote_token(*scene), builtin_scene_names(),
                             ", a .json scene file or a particle file (LAMMPS dump, extended XYZ, GSD, PLY)")};
  }
  if (auto e = resolve_particles(over_, trajectory(), particles_, fe_ == front_end::library)) throw refused(*e);
  if (whole_) shape_spheres(whole_->scene.spheres, particles_);
}

scene_source scene_source::from_text(const std::string& json, settings over, front_end fe) {
  scene_source s(fe, std::move(over));
  auto read = read_scene_text(json);
  if (auto* e = std::get_if<scene_file_error>(&read)) throw read_refusal(*e, "");
  s.whole_ = std::move(std::get<scene_file_contents>(read));
  if (auto e = resolve_particles(s.over_, false, s.particles_, fe == front_end::library)) throw refused(*e);
  shape_spheres(s.whole_->scene.spheres, s.particles_);
  return s;
}

scene_source::~scene_source() = default;
scene_source::scene_source(scene_source&&) noexcept = default;

void scene_source::open_file(const std::string& name) {
  file_ = name;
  const formats::detected f = formats::detect(name);
  if (!f)
    throw refusal{kind::invalid_argument, "", name,
                  "is not a scene file or a particle file of a format raycast reads (JSON, PLY, a LAMMPS dump, "
                  "extended XYZ, GSD)"};
  const auto start = steady::now();
  if (f.scene) {
    auto read = f.scene->read(name);
    if (auto* e = std::get_if<scene_file_error>(&read)) throw read_refusal(*e, name);
    whole_ = std::move(std::get<scene_file_contents>(read));
    whole_seconds_ = seconds_since(start);
    return;
  }
  try {
    traj_ = f.particles->open(name);
  } catch (const formats::format_error& e) {
    throw refusal{e.io ? kind::io : kind::invalid_argument, "", name, e.what()};
  }
}

size_t scene_source::frame_count() {
  if (!traj_) return 1;
  try {
    return traj_->frame_count();
  } catch (const formats::format_error& e) {
    throw refusal{e.io ? kind::io : kind::invalid_argument, "", file_, e.what()};
  }
}

bool scene_source::has_frame(size_t k) {
  if (!traj_) return k == 0;
  try {
    return traj_->has_frame(k);
  } catch (const formats::format_error& e) {
    throw refusal{e.io ? kind::io : kind::invalid_argument, "", file_, e.what()};
  }
}

described_scene scene_source::frame(size_t k) {
  if (traj_) return particle_frame_scene(k);
  scene_file_contents c = *whole_;  // a scene is the same every frame
  described_scene d = finish(std::move(c), file_, over_, fe_);
  d.load_seconds = whole_seconds_;
  return d;
}

described_scene scene_source::particle_frame_scene(size_t k) {
  const auto start = steady::now();
  formats::wanted_columns wanted;
  if (!particles_.color_by.empty()) wanted.properties.push_back(particles_.color_by);
  const auto read = [&](size_t i) {
    try {
      return traj_->read(i, wanted);
    } catch (const formats::format_error& e) {
      throw refusal{e.io ? kind::io : kind::invalid_argument, "", file_, e.what()};
    }
  };
  const auto spheres = [&](const particle_frame& f) {
    try {
      return spheres_of(f, particles_);
    } catch (const particle_refusal& e) {
      throw particle_refused(e, over_, file_);
    }
  };
  const particle_frame f = read(k);
  particle_spheres s = spheres(f);
  const double seconds = seconds_since(start);
  if (!framed_ && !placed(over_)) {  // the trajectory's first frame frames every frame
    if (k == 0) framed_ = framing_layer(f, s.arrays, over_, particles_, file_);
    else {
      const particle_frame first = read(0);
      framed_ = framing_layer(first, spheres(first).arrays, over_, particles_, file_);
    }
  }
  scene_file_contents c;
  if (framed_) c.keys = *framed_;
  c.scene.arrays = std::move(s.arrays);
  described_scene d = finish(std::move(c), file_, over_, fe_);
  d.load_seconds = seconds;
  d.note = std::move(s.note);
  return d;
}

described_scene describe_particles(const particle_frame& f, const settings& over, front_end fe, bool framed) {
  api::particles p;
  if (auto e = resolve_particles(over, true, p, fe == front_end::library)) throw refused(*e);
  particle_spheres s;
  try {
    s = spheres_of(f, p);
  } catch (const particle_refusal& e) {
    throw particle_refused(e, over, "");
  }
  scene_file_contents c;
  if (framed && !placed(over)) c.keys = framing_layer(f, s.arrays, over, p, "");
  c.scene.arrays = std::move(s.arrays);
  described_scene d = finish(std::move(c), "", over, fe);
  d.note = std::move(s.note);
  return d;
}

described_scene describe(const std::optional<std::string>& scene, const settings& over, front_end fe) {
  return scene_source(scene, over, fe).frame(0);
}

described_scene describe_text(const std::string& json, const settings& over, front_end fe) {
  return scene_source::from_text(json, over, fe).frame(0);
}

}  // namespace raycast
