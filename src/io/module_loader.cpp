#include "module_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <string>

#include "io_error.h"
#include "signals.h"

namespace raycast::io {
namespace {

std::string executable_dir() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  std::string path(buf, size_t(n));
  return path.substr(0, path.find_last_of('/'));
}

}  // namespace

const raycast_image_module* load_image_module(const std::string& for_file) {
  static const raycast_image_module* cached = nullptr;
  if (cached) return cached;
  const std::string dir = executable_dir();
  // The error to report: that of the first candidate that is there (a
  // library that cannot be mapped under an address-space limit, say), or
  // else that of the first candidate ("cannot open shared object file").
  std::string first_error, first_present_error;
  const std::string what = for_file + ": cannot load the image module";
  for (const std::string& candidate :
       {dir + "/raycast_oiio.so", dir + "/" RAYCAST_MODULE_RELDIR "/raycast_oiio.so"}) {
    std::string error;
    {
      // dlopen runs the static constructors of OpenImageIO's libraries, which
      // abort or crash when memory or threads run short: one line, exit 1.
      const crash_means_failure crash(what);
      if (void* h = dlopen(candidate.c_str(), RTLD_LAZY | RTLD_LOCAL)) {
        using get_fn = const raycast_image_module* (*)();
        auto get = reinterpret_cast<get_fn>(dlsym(h, "raycast_image_module_get"));
        const raycast_image_module* m = get ? get() : nullptr;
        if (m && m->abi_version == RAYCAST_IMAGE_MODULE_ABI) return cached = m;
        error = candidate + ": not a raycast image module of this version";
      } else {
        const char* e = dlerror();
        error = e ? e : candidate;
      }
    }
    if (first_error.empty()) first_error = error;
    if (first_present_error.empty() && access(candidate.c_str(), F_OK) == 0) first_present_error = error;
  }
  throw io_error(what + " (" + (first_present_error.empty() ? first_error : first_present_error) + ")");
}

}  // namespace raycast::io
