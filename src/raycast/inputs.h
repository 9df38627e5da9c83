// The whole input table (scene/settings.h): the scene's rows (camera and
// sky, also a scene file's keys), then the run's (output, format, backend,
// samples, ...), whose names come from their own rooms: backends and
// precisions from render/backend.h, samplers from scene/sampler.h, formats
// from io/format.h. The command line is built from it (cli/options.cpp);
// the library and the Python module check their options with its rows.
#pragma once
#include <span>

#include "scene/settings.h"

namespace raycast {

std::span<const setting> input_table();
const setting& input_row(setting_id id);

}  // namespace raycast
