#include "video/rgba_to_yuv.h"

#include <stdexcept>
#include <string>

extern "C" {
#include <libavutil/pixdesc.h>
}

namespace coinroll::video::detail {

// Measured by bench/video_bench.cpp on a 1280x720 frame with sharp edges and gradients, against a
// double-precision BT.709 reference (luma per pixel, chroma the mean of each 2x2 block):
//   flags                         ms/frame  luma rms  chroma rms  RGBA->YUV->RGBA PSNR
//   BILINEAR                      1.51      0.286     2.56        32.1 dB
//   BICUBIC                       1.55      0.286     1.45        33.0 dB
//   BICUBIC|ACCURATE_RND          1.65      0.286     1.44        33.0 dB
//   ... |FULL_CHR_H_INT           1.73      0.286     1.44        33.0 dB
// Luma is exact to rounding (rms 1/sqrt(12)) with every set; the filter decides the chroma, and
// bicubic's 2:1 chroma reduction is clearly closer than bilinear's. ACCURATE_RND trims the chroma
// error a little more for ~0.1 ms, under 1% of the ~19 ms single-threaded x264 veryfast spends
// on such a frame. FULL_CHR_H_INT only affects YUV -> RGB output, so it buys nothing here (same
// numbers); its input-side twin FULL_CHR_H_INP was worse (chroma rms 1.91).
const int kRgbaToYuvScalerFlags = SWS_BICUBIC | SWS_ACCURATE_RND;

ScalerPtr makeRgbaToYuvScaler(int width, int height, int flags, AVPixelFormat destination) {
  ScalerPtr scaler(
      sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height, destination, flags, nullptr, nullptr, nullptr));
  const std::string name = av_get_pix_fmt_name(destination);
  if (!scaler) {
    throw std::runtime_error("cannot create the RGBA to " + name + " converter for " + std::to_string(width) + "x" +
                             std::to_string(height));
  }
  // swscale defaults to the BT.601 matrix; the stream is tagged BT.709, so convert with BT.709.
  // Source full range: rendered RGBA uses all of 0..255. Destination limited range (luma 16..235),
  // what players assume for H.264 and what the stream says.
  const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
  setScalerColorDetails(*scaler, bt709, true, bt709, false,
                        "setting BT.709 limited range on the RGBA to " + name + " converter");
  return scaler;
}

void convertRgbaToYuv(SwsContext& scaler, const image::Image& rgba, AVFrame& yuv) {
  const std::uint8_t* const sourcePlanes[] = {rgba.rgba.data()};
  const int sourceStrides[] = {rgba.width * 4};
  checkAv(sws_scale(&scaler, sourcePlanes, sourceStrides, 0, rgba.height, yuv.data, yuv.linesize),
          "converting a frame from RGBA to YUV");
}

}  // namespace coinroll::video::detail
