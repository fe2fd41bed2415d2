#pragma once
// Images the renderer draws with, from assets/: read at run time from $COINROLL_ASSET_DIR when
// set, else the source tree's assets/ when present, else the copies embedded at build time.

#include <string_view>

#include "image/image.h"

namespace coinroll::render {

// Throws std::runtime_error naming the asset and where it looked if it cannot be read.
image::Image loadAssetImage(std::string_view name);

}  // namespace coinroll::render
