// The C interface between the raycast CLI and its image module
// (raycast_oiio.so), which is the only code that links OpenImageIO.
//
// The CLI loads the module with dlopen only when a format needs it, so a PPM
// render never pays the ~165 ms and ~130 MiB it costs to load Debian's
// OpenImageIO and its ~260 libraries.
//
// The module writes encoded bytes to a file descriptor the caller owns, through
// an OpenImageIO IOProxy that records the first failed write (errno) and
// reports it when the image is closed. Because the proxy never reports a short
// write to the encoder, a library that would abort on one (libjpeg's default
// error exit) keeps running, and the caller still learns of the failure.
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
  // format: "png", "jpg", "tif", "exr". Channels are RGB, 8-bit unless
  // is_float (32-bit float). timestamp: seconds since 1970 UTC to record as
  // the image's DateTime (EXR, TIFF), or -1 for now. fd may be a pipe for
  // formats that write in order (PNG, JPEG). Returns null and fills err on
  // failure. The caller keeps the libraries' own messages off standard error.
  raycast_image_writer* (*open)(int fd, const char* format, int64_t width, int64_t height,
                                int is_float, int64_t timestamp, char* err, size_t errlen);
  // Rows [y0, y1), top first; row y starts at data + (y - y0) * stride.
  // Returns 0 on success.
  int (*write_rows)(raycast_image_writer* w, int64_t y0, int64_t y1, const void* data,
                    size_t stride, char* err, size_t errlen);
  // Finishes the file and frees the writer, whatever happens. Returns 0 when
  // every byte reached the file descriptor.
  int (*close)(raycast_image_writer* w, char* err, size_t errlen);
  // Frees the writer of an image that will be discarded (a write failed, or
  // anything else stopped the render). The encoder is still closed, which can
  // take a moment (libjpeg encodes the missing rows), but nothing it says
  // about the file it could not finish reaches standard error: the caller
  // reports the failure, once.
  void (*abandon)(raycast_image_writer* w);
} raycast_image_module;

// The one exported symbol.
const raycast_image_module* raycast_image_module_get(void);

#ifdef __cplusplus
}
#endif
