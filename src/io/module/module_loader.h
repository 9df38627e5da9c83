// Finds and loads the image module (image_module.h) with dlopen, once per process.
#pragma once
#include <string>

#include "io/module/image_module.h"

namespace raycast::io {

// Beside the executable, or in <prefix>/<libdir>/raycast relative to <prefix>/bin. Throws
// io_error("<for_file>: cannot load the image module (<loader error>)").
const raycast_image_module* load_image_module(const std::string& for_file);

// One more folder to look in, before the executable's (a library's users); before the first load.
void add_image_module_dir(const std::string& dir);

}  // namespace raycast::io
