#include "module_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <string>

#include "io_error.h"

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
  std::string tried, last_error;
  for (const std::string& candidate :
       {dir + "/raycast_oiio.so", dir + "/" RAYCAST_MODULE_RELDIR "/raycast_oiio.so"}) {
    void* h = dlopen(candidate.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!h) {
      const char* e = dlerror();
      last_error = e ? e : candidate;
      continue;
    }
    using get_fn = const raycast_image_module* (*)();
    auto get = reinterpret_cast<get_fn>(dlsym(h, "raycast_image_module_get"));
    const raycast_image_module* m = get ? get() : nullptr;
    if (!m || m->abi_version != RAYCAST_IMAGE_MODULE_ABI) {
      last_error = candidate + ": not a raycast image module of this version";
      continue;
    }
    return cached = m;
  }
  throw io_error(for_file + ": cannot load the image module (" + last_error + ")");
}

}  // namespace raycast::io
