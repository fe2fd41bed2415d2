#include "video/rgba_to_yuv.h"

#include <stdexcept>

namespace coinroll::video::detail {

// PLACEHOLDER_FLAGS_COMMENT
const int kRgbaToYuvScalerFlags = SWS_BICUBIC;

ScalerPtr makeRgbaToYuvScaler(int width, int height, int flags) {
  ScalerPtr scaler(sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height, AV_PIX_FMT_YUV420P, flags,
                                  nullptr, nullptr, nullptr));
  if (!scaler) {
    throw std::runtime_error("cannot create the RGBA to yuv420p converter for " + std::to_string(width) + "x" +
                             std::to_string(height));
  }
  // swscale defaults to the BT.601 matrix; the stream is tagged BT.709, so convert with BT.709.
  // Source range 1: rendered RGBA uses all of 0..255. Destination range 0: limited (16..235 luma),
  // what players assume for H.264 and what the stream says. Brightness 0, contrast and
  // saturation 1.0 in swscale's 16.16 fixed point.
  const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
  constexpr int kUnity = 1 << 16;
  checkAv(sws_setColorspaceDetails(scaler.get(), bt709, 1, bt709, 0, 0, kUnity, kUnity),
          "setting BT.709 limited range on the RGBA to yuv420p converter");
  return scaler;
}

void convertRgbaToYuv(SwsContext& scaler, const image::Image& rgba, AVFrame& yuv) {
  const std::uint8_t* const sourcePlanes[] = {rgba.rgba.data()};
  const int sourceStrides[] = {rgba.width * 4};
  checkAv(sws_scale(&scaler, sourcePlanes, sourceStrides, 0, rgba.height, yuv.data, yuv.linesize),
          "converting a frame from RGBA to yuv420p");
}

}  // namespace coinroll::video::detail
