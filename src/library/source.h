// What --scene names, opened once for a run: a built-in scene or a scene
// file (read whole: one frame), or a particle file's trajectory (its frames
// read one at a time, each made spheres as the particle options ask and seen
// through the camera the trajectory's first frame frames). Each frame comes
// out described (raycast/description.h): the front end's settings over the
// file's keys (or the framing), resolved, every rule checked, a refusal
// blaming whoever gave the value.
#pragma once
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "formats/format.h"
#include "formats/json.h"
#include "library/pipeline.h"

namespace raycast {

struct described_scene {
  api::scene scene;
  std::string file;         // the scene file's name, "" for a built-in scene or text
  double load_seconds = 0;  // reading and parsing the file (a trajectory: this frame)
  std::string note;         // said to whoever watches (particle/spheres.h's)
};

class scene_source {
 public:
  // none: the lesson's sky. Throws refusal.
  scene_source(const std::optional<std::string>& scene, settings over, front_end fe);
  // A scene file's text (Python's dict scenes).
  static scene_source from_text(const std::string& json, settings over, front_end fe);
  ~scene_source();
  scene_source(scene_source&&) noexcept;

  bool trajectory() const { return traj_ != nullptr; }
  size_t frame_count();  // 1 but for a trajectory: its frames, the file scanned once
  bool has_frame(size_t k);  // the file scanned only as far as frame k
  // Frame k's scene (k < frame_count()). Throws refusal: a frame the file
  // cannot give names the frame and where in the file.
  described_scene frame(size_t k);
  const std::string& file() const { return file_; }
  // A scene file's camera, sky and light keys (none for the rest).
  settings keys() const { return whole_ ? whole_->keys : settings{}; }

 private:
  scene_source(front_end fe, settings over) : fe_(fe), over_(std::move(over)) {}
  void open_file(const std::string& name);
  described_scene particle_frame_scene(size_t k);

  front_end fe_;
  settings over_;
  std::string file_;
  api::particles particles_;
  std::optional<scene_file_contents> whole_;  // a scene's, read at opening
  double whole_seconds_ = 0;
  std::unique_ptr<formats::trajectory> traj_;
  std::optional<settings> framed_;  // the first frame's framing, once computed
};

// Particle data from elsewhere (a caller's arrays) as a scene: made spheres
// as `over`'s particle rows ask, seen through `over`'s camera or, with
// `framed` and no camera placed, framed (particles/framing.h).
described_scene describe_particles(const particle_frame& f, const settings& over, front_end fe, bool framed);

// One frame's scene: scene_source(scene, over, fe).frame(0).
described_scene describe(const std::optional<std::string>& scene, const settings& over, front_end fe);
described_scene describe_text(const std::string& json, const settings& over, front_end fe);

}  // namespace raycast
