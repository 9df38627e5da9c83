#include "scene/scene_file.h"

#include <cmath>
#include <initializer_list>

#include <nlohmann/json.hpp>

namespace raycast {
namespace {

using json = nlohmann::json;

// Thrown inside the parser only; parse_scene_file turns it into its result.
struct failure {
  scene_file_error e;
};

[[noreturn]] void fail(const std::string& path, const std::string& why) { throw failure{{path, why}}; }

void only_keys(const json& obj, const std::string& path, std::initializer_list<std::string_view> keys) {
  if (!obj.is_object()) fail(path, "must be an object");
  for (const auto& [k, v] : obj.items()) {
    bool known = false;
    for (std::string_view key : keys) known = known || k == key;
    if (!known) {
      std::string list;
      for (std::string_view key : keys) list += (list.empty() ? "" : ", ") + std::string(key);
      fail(path.empty() ? k : path + "." + k, "unknown key (known here: " + list + ")");
    }
  }
}

double number(const json& v, const std::string& path) {
  if (!v.is_number()) fail(path, "must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(path, "must be finite");
  return x;
}

vec3 triple(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() != 3) fail(path, "must be an array of 3 numbers");
  vec3 r;
  for (int k = 0; k < 3; ++k) r[k] = number(v[size_t(k)], path + "[" + std::to_string(k) + "]");
  return r;
}

int64_t integer(const json& v, const std::string& path) {
  if (!v.is_number_integer()) fail(path, "must be an integer");
  if (v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(INT64_MAX)) fail(path, "is out of range");
  return v.get<int64_t>();
}

double aspect(const json& v, const std::string& path) {
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    const size_t colon = s.find(':');
    size_t used_w = 0, used_h = 0;
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      const double w = std::stod(s.substr(0, colon), &used_w);
      const double h = std::stod(s.substr(colon + 1), &used_h);
      if (used_w != colon || used_h != s.size() - colon - 1 || !(w > 0 && h > 0) || !std::isfinite(w / h))
        throw std::invalid_argument("bad");
      return w / h;
    } catch (const std::exception&) {
      fail(path, "must be a number or \"W:H\" with positive W and H");
    }
  }
  return number(v, path);
}

scene_params read(const json& root) {
  scene_params p;
  only_keys(root, "", {"camera", "sky", "spheres"});
  if (root.contains("camera")) {
    const json& c = root["camera"];
    only_keys(c, "camera", {"width", "height", "aspect", "lookfrom", "lookat", "vup", "vfov",
                            "viewport_height", "focal_length"});
    camera_params& cp = p.camera;
    if (c.contains("width")) cp.image_width = integer(c["width"], "camera.width");
    if (c.contains("height")) cp.image_height = integer(c["height"], "camera.height");
    if (c.contains("aspect")) cp.aspect_ratio = aspect(c["aspect"], "camera.aspect");
    if (c.contains("lookfrom")) cp.origin = triple(c["lookfrom"], "camera.lookfrom");
    if (c.contains("lookat")) cp.lookat = triple(c["lookat"], "camera.lookat");
    if (c.contains("vup")) {
      cp.vup = triple(c["vup"], "camera.vup");
      if (!cp.lookat) cp.lookat = cp.origin + vec3(0.0, 0.0, -1.0);  // the lesson's view, as the CLI
    }
    if (c.contains("vfov")) cp.vfov_degrees = number(c["vfov"], "camera.vfov");
    if (c.contains("viewport_height")) {
      if (cp.vfov_degrees) fail("camera.viewport_height", "give vfov or viewport_height, not both");
      cp.viewport_height = number(c["viewport_height"], "camera.viewport_height");
    }
    if (c.contains("focal_length")) cp.focal_length = number(c["focal_length"], "camera.focal_length");
  }
  if (root.contains("sky")) {
    const json& s = root["sky"];
    only_keys(s, "sky", {"bottom", "top"});
    if (s.contains("bottom")) p.sky.bottom = triple(s["bottom"], "sky.bottom");
    if (s.contains("top")) p.sky.top = triple(s["top"], "sky.top");
  }
  if (root.contains("spheres")) {
    const json& list = root["spheres"];
    if (!list.is_array()) fail("spheres", "must be an array");
    p.spheres.reserve(list.size());
    for (size_t k = 0; k < list.size(); ++k) {
      const std::string at = "spheres[" + std::to_string(k) + "]";
      const json& s = list[k];
      only_keys(s, at, {"center", "radius", "shade", "color"});
      sphere sp;
      if (!s.contains("center")) fail(at + ".center", "is required");
      if (!s.contains("radius")) fail(at + ".radius", "is required");
      sp.center = triple(s["center"], at + ".center");
      sp.radius = number(s["radius"], at + ".radius");
      if (s.contains("shade")) {
        const json& sh = s["shade"];
        if (!sh.is_string() || (sh != "normal" && sh != "flat"))
          fail(at + ".shade", "must be \"normal\" or \"flat\"");
        sp.shade = sh == "flat" ? shading::flat : shading::normal;
      }
      if (sp.shade == shading::flat && !s.contains("color")) fail(at + ".color", "is required for flat shading");
      if (s.contains("color")) sp.flat_color = triple(s["color"], at + ".color");
      p.spheres.push_back(sp);
    }
  }
  return p;
}

}  // namespace

std::variant<scene_params, scene_file_error> parse_scene_file(std::string_view text) {
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    return scene_file_error{"", "not valid JSON (at byte " + std::to_string(e.byte) + ")"};
  } catch (const json::exception& e) {  // a number beyond a double: "number overflow parsing '1e999'"
    const std::string what = e.what();
    return scene_file_error{"", "not valid JSON: " + what.substr(what.find(']') + 2)};
  }
  try {
    scene_params p = read(root);
    for (size_t k = 0; k < p.spheres.size(); ++k)
      if (auto e = validate(p.spheres[k], k)) return scene_file_error{path(*e), e->message};
    return p;
  } catch (const failure& x) {
    return x.e;
  }
}

}  // namespace raycast
