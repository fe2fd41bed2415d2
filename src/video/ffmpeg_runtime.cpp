// FFmpeg's functions that src/video calls, opened at the first call (io/runtime_library.h): a
// command that writes no video never loads FFmpeg and the hundred libraries it depends on. The
// sonames are those of the headers coinroll was built against (src/video/CMakeLists.txt).

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/channel_layout.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/frame.h>
#include <libavutil/log.h>
#include <libavutil/mathematics.h>
#include <libavutil/opt.h>
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

#include "io/runtime_library.h"

namespace {

using coinroll::io::RuntimeLibrary;

RuntimeLibrary& avutil() {
  static RuntimeLibrary library(COINROLL_AVUTIL_SONAME, COINROLL_AVUTIL_PACKAGE);
  return library;
}
RuntimeLibrary& avcodec() {
  static RuntimeLibrary library(COINROLL_AVCODEC_SONAME, COINROLL_AVCODEC_PACKAGE);
  return library;
}
RuntimeLibrary& avformat() {
  static RuntimeLibrary library(COINROLL_AVFORMAT_SONAME, COINROLL_AVFORMAT_PACKAGE);
  return library;
}
RuntimeLibrary& swscale() {
  static RuntimeLibrary library(COINROLL_SWSCALE_SONAME, COINROLL_SWSCALE_PACKAGE);
  return library;
}

}  // namespace

COINROLL_FORWARD(avutil(), int, av_channel_layout_copy, (AVChannelLayout * dst, const AVChannelLayout* src), (dst, src))
COINROLL_FORWARD(avutil(), void, av_channel_layout_default, (AVChannelLayout * layout, int channels),
                 (layout, channels))
COINROLL_FORWARD(avutil(), int, av_dict_count, (const AVDictionary* m), (m))
COINROLL_FORWARD(avutil(), void, av_dict_free, (AVDictionary * *m), (m))
COINROLL_FORWARD(avutil(), AVDictionaryEntry*, av_dict_get,
                 (const AVDictionary* m, const char* key, const AVDictionaryEntry* prev, int flags),
                 (m, key, prev, flags))
COINROLL_FORWARD(avutil(), int, av_dict_set, (AVDictionary * *pm, const char* key, const char* value, int flags),
                 (pm, key, value, flags))
COINROLL_FORWARD(avutil(), AVFrame*, av_frame_alloc, (void), ())
COINROLL_FORWARD(avutil(), void, av_frame_free, (AVFrame * *frame), (frame))
COINROLL_FORWARD(avutil(), int, av_frame_get_buffer, (AVFrame * frame, int align), (frame, align))
COINROLL_FORWARD(avutil(), int, av_frame_make_writable, (AVFrame * frame), (frame))
COINROLL_FORWARD(avutil(), enum AVPixelFormat, av_get_pix_fmt, (const char* name), (name))
COINROLL_FORWARD(avutil(), const char*, av_get_pix_fmt_name, (enum AVPixelFormat format), (format))
COINROLL_FORWARD(avutil(), int, av_log_get_level, (void), ())
COINROLL_FORWARD(avutil(), void, av_log_set_level, (int level), (level))
COINROLL_FORWARD(avutil(), int, av_opt_set, (void* obj, const char* name, const char* val, int search_flags),
                 (obj, name, val, search_flags))
COINROLL_FORWARD(avutil(), int, av_opt_set_int, (void* obj, const char* name, int64_t val, int search_flags),
                 (obj, name, val, search_flags))
COINROLL_FORWARD(avutil(), const AVPixFmtDescriptor*, av_pix_fmt_desc_get, (enum AVPixelFormat format), (format))
COINROLL_FORWARD(avutil(), enum AVPixelFormat, av_pix_fmt_desc_get_id, (const AVPixFmtDescriptor* desc), (desc))
COINROLL_FORWARD(avutil(), int64_t, av_rescale_q, (int64_t a, AVRational bq, AVRational cq), (a, bq, cq))
COINROLL_FORWARD(avutil(), int, av_strerror, (int errnum, char* errbuf, size_t errbuf_size),
                 (errnum, errbuf, errbuf_size))

COINROLL_FORWARD(avcodec(), AVPacket*, av_packet_alloc, (void), ())
COINROLL_FORWARD(avcodec(), void, av_packet_free, (AVPacket * *packet), (packet))
COINROLL_FORWARD(avcodec(), void, av_packet_rescale_ts, (AVPacket * packet, AVRational from, AVRational to),
                 (packet, from, to))
COINROLL_FORWARD(avcodec(), AVCodecContext*, avcodec_alloc_context3, (const AVCodec* codec), (codec))
COINROLL_FORWARD(avcodec(), const AVCodec*, avcodec_find_encoder, (enum AVCodecID id), (id))
COINROLL_FORWARD(avcodec(), const AVCodec*, avcodec_find_encoder_by_name, (const char* name), (name))
COINROLL_FORWARD(avcodec(), void, avcodec_free_context, (AVCodecContext * *context), (context))
COINROLL_FORWARD(avcodec(), int, avcodec_open2,
                 (AVCodecContext * context, const AVCodec* codec, AVDictionary** options), (context, codec, options))
COINROLL_FORWARD(avcodec(), int, avcodec_parameters_from_context,
                 (AVCodecParameters * parameters, const AVCodecContext* context), (parameters, context))
COINROLL_FORWARD(avcodec(), int, avcodec_receive_packet, (AVCodecContext * context, AVPacket* packet),
                 (context, packet))
COINROLL_FORWARD(avcodec(), int, avcodec_send_frame, (AVCodecContext * context, const AVFrame* frame), (context, frame))

COINROLL_FORWARD(avformat(), int, av_interleaved_write_frame, (AVFormatContext * s, AVPacket* packet), (s, packet))
COINROLL_FORWARD(avformat(), int, av_write_trailer, (AVFormatContext * s), (s))
COINROLL_FORWARD(avformat(), int, avformat_alloc_output_context2,
                 (AVFormatContext * *context, const AVOutputFormat* format, const char* format_name,
                  const char* filename),
                 (context, format, format_name, filename))
COINROLL_FORWARD(avformat(), void, avformat_close_input, (AVFormatContext * *s), (s))
COINROLL_FORWARD(avformat(), void, avformat_free_context, (AVFormatContext * s), (s))
COINROLL_FORWARD(avformat(), int, avformat_init_output, (AVFormatContext * s, AVDictionary** options), (s, options))
COINROLL_FORWARD(avformat(), AVStream*, avformat_new_stream, (AVFormatContext * s, const AVCodec* codec), (s, codec))
COINROLL_FORWARD(avformat(), int, avformat_open_input,
                 (AVFormatContext * *s, const char* url, const AVInputFormat* format, AVDictionary** options),
                 (s, url, format, options))
COINROLL_FORWARD(avformat(), int, avformat_write_header, (AVFormatContext * s, AVDictionary** options), (s, options))
COINROLL_FORWARD(avformat(), int, avio_closep, (AVIOContext * *s), (s))
COINROLL_FORWARD(avformat(), int, avio_open, (AVIOContext * *s, const char* url, int flags), (s, url, flags))

COINROLL_FORWARD(swscale(), void, sws_freeContext, (struct SwsContext * context), (context))
COINROLL_FORWARD(swscale(), const int*, sws_getCoefficients, (int colorspace), (colorspace))
COINROLL_FORWARD(swscale(), struct SwsContext*, sws_getContext,
                 (int srcW, int srcH, enum AVPixelFormat srcFormat, int dstW, int dstH, enum AVPixelFormat dstFormat,
                  int flags, SwsFilter* srcFilter, SwsFilter* dstFilter, const double* param),
                 (srcW, srcH, srcFormat, dstW, dstH, dstFormat, flags, srcFilter, dstFilter, param))
COINROLL_FORWARD(swscale(), int, sws_scale,
                 (struct SwsContext * context, const uint8_t* const srcSlice[], const int srcStride[], int srcSliceY,
                  int srcSliceH, uint8_t* const dst[], const int dstStride[]),
                 (context, srcSlice, srcStride, srcSliceY, srcSliceH, dst, dstStride))
COINROLL_FORWARD(swscale(), int, sws_setColorspaceDetails,
                 (struct SwsContext * context, const int inv_table[4], int srcRange, const int table[4], int dstRange,
                  int brightness, int contrast, int saturation),
                 (context, inv_table, srcRange, table, dstRange, brightness, contrast, saturation))
