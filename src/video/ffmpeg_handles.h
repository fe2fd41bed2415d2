#pragma once
// Internal to src/video: owning handles for FFmpeg objects and the one way FFmpeg errors become
// exceptions. Every object is freed by its handle, so an exception thrown halfway through
// setting up an encoder or demuxer leaks nothing and closes every file it opened.

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/frame.h>
#include <libswscale/swscale.h>
}

#include <cerrno>
#include <memory>
#include <stdexcept>
#include <string>

#include "io/output_file.h"

namespace coinroll::video::detail {

// Muxer side: closes the file it wrote through (unless the format has none), then frees.
struct OutputFormatDeleter {
  void operator()(AVFormatContext* context) const {
    if (context->pb != nullptr && (context->oformat->flags & AVFMT_NOFILE) == 0) avio_closep(&context->pb);
    avformat_free_context(context);
  }
};
struct InputFormatDeleter {
  void operator()(AVFormatContext* context) const { avformat_close_input(&context); }
};
struct CodecContextDeleter {
  void operator()(AVCodecContext* context) const { avcodec_free_context(&context); }
};
struct FrameDeleter {
  void operator()(AVFrame* frame) const { av_frame_free(&frame); }
};
struct PacketDeleter {
  void operator()(AVPacket* packet) const { av_packet_free(&packet); }
};
struct ScalerDeleter {
  void operator()(SwsContext* scaler) const { sws_freeContext(scaler); }
};
struct DictionaryDeleter {
  void operator()(AVDictionary* dictionary) const { av_dict_free(&dictionary); }
};

using OutputFormatPtr = std::unique_ptr<AVFormatContext, OutputFormatDeleter>;
using InputFormatPtr = std::unique_ptr<AVFormatContext, InputFormatDeleter>;
using CodecContextPtr = std::unique_ptr<AVCodecContext, CodecContextDeleter>;
using FramePtr = std::unique_ptr<AVFrame, FrameDeleter>;
using PacketPtr = std::unique_ptr<AVPacket, PacketDeleter>;
using ScalerPtr = std::unique_ptr<SwsContext, ScalerDeleter>;
using DictionaryPtr = std::unique_ptr<AVDictionary, DictionaryDeleter>;

// FFmpeg's text for an AVERROR code (what av_err2str gives, without its C99 compound literal).
inline std::string describeAvError(int errorCode) {
  if (errorCode == AVERROR(EFBIG)) return io::describeWriteError(EFBIG);  // names the limit reached
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  if (av_strerror(errorCode, text, sizeof text) < 0) return "unknown FFmpeg error " + std::to_string(errorCode);
  return text;
}

// Passes a non-negative FFmpeg result through; a negative one throws std::runtime_error
// "<what>: <FFmpeg's text>", where `what` names the file and the step that failed.
inline int checkAv(int result, const std::string& what) {
  if (result < 0) throw std::runtime_error(what + ": " + describeAvError(result));
  return result;
}

// Throws std::runtime_error("<what>: out of memory") when an FFmpeg allocator returned null.
template <typename T>
T* checkAllocated(T* object, const std::string& what) {
  if (object == nullptr) throw std::runtime_error(what + ": out of memory");
  return object;
}

// Sets the YUV matrix (sws_getCoefficients) and ranges (true = full 0..255, false = limited) of a
// conversion, keeping brightness, contrast and saturation neutral. Throws std::runtime_error
// "<what>: ..." if swscale refuses (it returns -1, not an AVERROR code, so there is no text).
inline void setScalerColorDetails(SwsContext& scaler, const int* sourceMatrix, bool isSourceFullRange,
                                  const int* destinationMatrix, bool isDestinationFullRange, const std::string& what) {
  constexpr int kUnity = 1 << 16;  // 1.0 in swscale's 16.16 fixed point
  if (sws_setColorspaceDetails(&scaler, sourceMatrix, isSourceFullRange ? 1 : 0, destinationMatrix,
                               isDestinationFullRange ? 1 : 0, 0, kUnity, kUnity) < 0) {
    throw std::runtime_error(what + ": swscale does not support these colour details for this conversion");
  }
}

}  // namespace coinroll::video::detail
