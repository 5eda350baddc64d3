// The pictures of image patterns in the browser's build (TRACER_WEB), which has no image library:
// the page decodes them (the browser reads PNG and JPEG) and hands them over by path before the
// scene that names them loads; io/image_file.h's load_images then takes them from here.
#pragma once

#include <string>

#include "scene/pattern.h"

namespace tracer {

// Keeps `texels` as the picture of the file at `path` (absolute), for every later load.
void provide_picture(const std::string& path, Texels texels);

}  // namespace tracer
