// The yardstick for `raycast -o sky.png`: a bare program that links
// OpenImageIO and writes the same 400x225 PNG with no temporary file, no
// module loading and no error handling. bench/startup.sh times both.
#include <OpenImageIO/imageio.h>

#include <vector>

#include "render/render.h"

int main(int argc, char** argv) {
  const char* path = argc > 1 ? argv[1] : "baseline.png";
  const raycast::scene s{raycast::make_camera({}), {}, {}, std::nullopt, {}};
  const int64_t W = s.cam.image_width, H = s.cam.image_height;
  std::vector<unsigned char> pixels(size_t(W * H * 3));
  raycast::renderer(s, {}).render(
      {pixels.data(), size_t(W) * 3, raycast::pixel_format::rgb8, 0, H});
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, OIIO::ImageSpec(int(W), int(H), 3, OIIO::TypeDesc::UINT8))) return 1;
  const bool ok = out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) && out->close();
  return ok ? 0 : 1;
}
