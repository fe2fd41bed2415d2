#pragma once
// Internal to src/video (and bench/): the RGBA -> yuv420p conversion the MP4 encoder uses, in
// one place so the benchmark measures exactly what the sink does.

#include "image/image.h"
#include "video/ffmpeg_handles.h"

namespace coinroll::video::detail {

// Chosen by bench/video_bench.cpp (see the comment at the definition for the numbers).
extern const int kRgbaToYuvScalerFlags;

// A scaler from width x height RGBA (full range, as rendered) to `destination` (a YUV format,
// with or without alpha) with BT.709 matrix and limited range, the tags EncoderSink writes.
// `flags` are SWS_* flags. Throws std::runtime_error.
ScalerPtr makeRgbaToYuvScaler(int width, int height, int flags, AVPixelFormat destination = AV_PIX_FMT_YUV420P);

// Converts `rgba` into the planes of `yuv` (allocated, the scaler's format, same size as `rgba`).
void convertRgbaToYuv(SwsContext& scaler, const image::Image& rgba, AVFrame& yuv);

}  // namespace coinroll::video::detail
