// The C interface to the image module (raycast_oiio.so, the only code that links OpenImageIO). It
// writes to the caller's file descriptor through a proxy that reports the first failed write at
// close: the encoder never sees a short write (libjpeg would exit on one).
#pragma once
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RAYCAST_IMAGE_MODULE_ABI 3

typedef struct raycast_image_writer raycast_image_writer;

typedef struct raycast_image_module {
  int abi_version;  // RAYCAST_IMAGE_MODULE_ABI
  // format: "png", "jpg", "tif", "exr"; RGB, 8-bit unless is_float. timestamp: the DateTime to
  // record (EXR, TIFF), seconds since 1970 UTC, or -1 for now. fd may be a pipe for PNG and JPEG.
  // Returns null and fills err on failure.
  raycast_image_writer* (*open)(int fd, const char* format, int64_t width, int64_t height,
                                int is_float, int64_t timestamp, char* err, size_t errlen);
  // Rows [y0, y1), top first; row y starts at data + (y - y0) * stride. Returns 0 on success.
  int (*write_rows)(raycast_image_writer* w, int64_t y0, int64_t y1, const void* data,
                    size_t stride, char* err, size_t errlen);
  // Finishes the file and frees the writer; 0 when every byte reached the file descriptor.
  int (*close)(raycast_image_writer* w, char* err, size_t errlen);
  // Frees the writer of an image that will be discarded; the encoder is closed silently.
  void (*abandon)(raycast_image_writer* w);
} raycast_image_module;

// The one exported symbol.
const raycast_image_module* raycast_image_module_get(void);

#ifdef __cplusplus
}
#endif
