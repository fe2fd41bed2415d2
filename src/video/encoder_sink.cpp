#include "video/encoder_sink.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "io/output_file.h"
#include "video/ffmpeg_handles.h"
#include "video/gif_comment.h"
#include "video/gif_palette.h"
#include "video/rgba_to_yuv.h"

extern "C" {
#include <libavutil/channel_layout.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
}

namespace coinroll::video {

using namespace detail;

namespace {

std::string videoOptionError(const std::string& field, const std::string& rule, const std::string& value) {
  return "VideoOptions." + field + ": " + rule + ", got " + value;
}

// What each kind of file is made of (docs/outputs.md "Video formats").
struct Container {
  const char* label;          // in messages: "MP4"
  const char* muxer;          // libavformat's name; the temporary name has no extension to guess by
  const char* encoder;        // libavcodec's name
  AVPixelFormat pixelFormat;  // without alpha
  AVPixelFormat alphaFormat;  // with alpha (keepsAlpha); AV_PIX_FMT_NONE where the codec has none
  bool evenSides;             // 4:2:0 chroma: the picture's sides must be even
};

const Container& containerOf(VideoFormat format) {
  static const Container mp4{"MP4", "mp4", "libx264", AV_PIX_FMT_YUV420P, AV_PIX_FMT_NONE, true};
  static const Container gif{"GIF", "gif", "gif", AV_PIX_FMT_PAL8, AV_PIX_FMT_NONE, false};
  static const Container webm{"WebM", "webm", "libvpx-vp9", AV_PIX_FMT_YUV420P, AV_PIX_FMT_YUVA420P, true};
  static const Container mov{"MOV", "mov", "prores_ks", AV_PIX_FMT_YUV444P10LE, AV_PIX_FMT_YUVA444P10LE, false};
  switch (format) {
    case VideoFormat::Mp4: return mp4;
    case VideoFormat::Gif: return gif;
    case VideoFormat::WebM: return webm;
    case VideoFormat::Mov: return mov;
  }
  throw std::logic_error("unknown VideoFormat");
}

// libvpx-vp9's settings (measured in docs/outputs.md "Video formats"): the realtime deadline at its
// fastest speed with row multithreading keeps a WebM within 3x an MP4's time; crf with no bit-rate
// cap is libvpx's constant-quality mode.
constexpr const char* kVp9Deadline = "realtime";
constexpr int kVp9CpuUsed = 8;
constexpr int kVp9Crf = 32;
// Fixed, as x264's are (X264Options::threads): the output must not follow the machine.
constexpr int kVp9Threads = 2;
// ProRes's quantiser, 1 (finest) .. 31 (prores_ks's qscale); 4 is near-lossless for these pictures.
constexpr int kProResQuantiser = 4;

}  // namespace

void validate(const VideoOptions& options) {
  const Container& container = containerOf(options.format);
  auto requireSide = [&](const char* field, int value) {
    if (value <= 0 || (container.evenSides && value % 2 != 0)) {
      throw std::invalid_argument(videoOptionError(
          field, container.evenSides ? "must be even and > 0 (4:2:0 chroma halves it)" : "must be > 0", std::to_string(value)));
    }
  };
  requireSide("width", options.width);
  requireSide("height", options.height);
  if (options.fps <= 0) throw std::invalid_argument(videoOptionError("fps", "must be > 0", std::to_string(options.fps)));
  const X264Options& x264 = options.x264;
  if (x264.crf < 0 || x264.crf > kMaxCrf) {
    throw std::invalid_argument(videoOptionError("x264.crf", "must be in 0.." + std::to_string(kMaxCrf), std::to_string(x264.crf)));
  }
  if (std::find(kX264Presets.begin(), kX264Presets.end(), x264.preset) == kX264Presets.end()) {
    std::string presets;
    for (const std::string_view preset : kX264Presets) presets += (presets.empty() ? "" : ", ") + std::string(preset);
    throw std::invalid_argument(videoOptionError("x264.preset", "must be an x264 preset (" + presets + ")", "'" + x264.preset + "'"));
  }
  if (x264.threads < 1 || x264.threads > kMaxX264Threads) {
    throw std::invalid_argument(
        videoOptionError("x264.threads", "must be in 1.." + std::to_string(kMaxX264Threads), std::to_string(x264.threads)));
  }
  if (options.alpha && !keepsAlpha(options.format)) {
    throw std::invalid_argument(videoOptionError("alpha", std::string(container.label) + " has no alpha channel", "true"));
  }
  if (options.audio && !holdsAudio(options.format)) {
    throw std::invalid_argument(videoOptionError("audio", std::string(container.label) + " gets no sound track", "true"));
  }
}

struct EncoderSink::Encoder {
  // Declared first so it is destroyed last, after the muxer has closed the temporary file.
  // ByPath: the muxer writes the file itself and rereads it for faststart, so a stream
  // destination (a pipe, /dev/stdout) gets the finished file copied to it by commit().
  io::OutputFile file;
  std::string context;  // "<destination>: " prefix for error messages
  const Container& container;
  OutputFormatPtr format;
  CodecContextPtr codec;
  AVStream* stream = nullptr;  // owned by `format`
  FramePtr frame;
  PacketPtr packet;
  ScalerPtr scaler;                          // RGBA to the YUV formats; none for GIF
  std::array<std::uint32_t, 256> palette{};  // GIF's (gifPalette()), copied into every frame

  // The AAC track, when asked for. AAC codes fixed blocks of frame_size samples, so samples wait
  // in `pending` until a block is full; the last, shorter block goes out at finish().
  CodecContextPtr audioCodec;
  AVStream* audioStream = nullptr;  // owned by `format`
  FramePtr audioFrame;
  std::vector<float> pending;
  std::int64_t audioSamplesSent = 0;

  Encoder(const std::filesystem::path& destination, const VideoOptions& options);

  // Sends `frame` (or nullptr to drain) to an encoder and muxes every packet it returns.
  void encode(AVCodecContext& encoder, AVStream& target, const AVFrame* frame, const char* what);
  // Encodes `count` samples from the front of `pending`.
  void encodeAudioBlock(int count);
  // Sets the video encoder's own options for `options.format`.
  void configureVideoCodec(const VideoOptions& options);
};

void EncoderSink::Encoder::configureVideoCodec(const VideoOptions& options) {
  void* settings = codec->priv_data;
  switch (options.format) {
    case VideoFormat::Mp4:
      codec->thread_count = options.x264.threads;
      checkAv(av_opt_set(settings, "preset", options.x264.preset.c_str(), 0), context + "setting x264 preset");
      checkAv(av_opt_set_double(settings, "crf", options.x264.crf, 0), context + "setting x264 crf");
      return;
    case VideoFormat::WebM:
      codec->thread_count = kVp9Threads;
      codec->bit_rate = 0;  // with crf: constant quality, no bit-rate target
      checkAv(av_opt_set(settings, "deadline", kVp9Deadline, 0), context + "setting the VP9 deadline");
      checkAv(av_opt_set_int(settings, "cpu-used", kVp9CpuUsed, 0), context + "setting VP9 cpu-used");
      checkAv(av_opt_set_int(settings, "row-mt", 1, 0), context + "setting VP9 row-mt");
      checkAv(av_opt_set_int(settings, "crf", kVp9Crf, 0), context + "setting VP9 crf");
      return;
    case VideoFormat::Mov:
      // One thread, as x264 (X264Options::threads): the renderer keeps the cores busy already.
      codec->thread_count = 1;
      // A fixed quantiser: prores_ks's default searches each slice's quantiser for the profile's
      // bit budget, 6x slower for no visible gain (docs/outputs.md "Video formats").
      codec->flags |= AV_CODEC_FLAG_QSCALE;
      codec->global_quality = kProResQuantiser * FF_QP2LAMBDA;
      checkAv(av_opt_set(settings, "profile", "4444", 0), context + "setting the ProRes 4444 profile");
      return;
    case VideoFormat::Gif:
      return;  // gifflags' defaults (offsetting, transdiff) code only what changed since the last frame
  }
}

EncoderSink::Encoder::Encoder(const std::filesystem::path& destination, const VideoOptions& options)
    : file(destination, containerOf(options.format).label, io::OutputFile::Access::ByPath),
      context(destination.string() + ": "),
      container(containerOf(options.format)) {
  const std::string temporary = file.temporaryPath().string();
  const std::string label = container.label;

  // The muxer is named, not guessed: the temporary name has no extension.
  AVFormatContext* rawFormat = nullptr;
  checkAv(avformat_alloc_output_context2(&rawFormat, nullptr, container.muxer, temporary.c_str()),
          context + "creating the " + label + " muxer");
  format.reset(rawFormat);
  // No encoder version string, no creation time, no random segment id: the same frames give the same bytes.
  format->flags |= AVFMT_FLAG_BITEXACT;

  const AVCodec* videoEncoder = avcodec_find_encoder_by_name(container.encoder);
  if (videoEncoder == nullptr) {
    throw std::runtime_error(context + "this FFmpeg build has no " + container.encoder + " encoder");
  }
  codec.reset(checkAllocated(avcodec_alloc_context3(videoEncoder), context + "allocating the " + container.encoder + " encoder"));
  codec->width = options.width;
  codec->height = options.height;
  codec->pix_fmt = options.alpha ? container.alphaFormat : container.pixelFormat;
  codec->time_base = AVRational{1, options.fps};
  codec->framerate = AVRational{options.fps, 1};
  const bool yuv = codec->pix_fmt != AV_PIX_FMT_PAL8;
  if (yuv) {
    codec->color_primaries = AVCOL_PRI_BT709;
    codec->color_trc = AVCOL_TRC_BT709;
    codec->colorspace = AVCOL_SPC_BT709;
    codec->color_range = AVCOL_RANGE_MPEG;
  }
  codec->flags |= AV_CODEC_FLAG_BITEXACT;
  if ((format->oformat->flags & AVFMT_GLOBALHEADER) != 0) codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  configureVideoCodec(options);
  checkAv(avcodec_open2(codec.get(), videoEncoder, nullptr), context + "opening the " + container.encoder + " encoder");

  stream = checkAllocated(avformat_new_stream(format.get(), nullptr), context + "adding the video stream");
  checkAv(avcodec_parameters_from_context(stream->codecpar, codec.get()),
          context + "copying encoder parameters to the stream");
  stream->time_base = codec->time_base;  // a hint; the muxer may choose a finer one
  stream->avg_frame_rate = codec->framerate;

  if (options.audio) {
    const AVCodec* aac = avcodec_find_encoder(AV_CODEC_ID_AAC);
    if (aac == nullptr) throw std::runtime_error(context + "this FFmpeg build has no AAC encoder");
    audioCodec.reset(checkAllocated(avcodec_alloc_context3(aac), context + "allocating the AAC encoder"));
    audioCodec->sample_fmt = AV_SAMPLE_FMT_FLTP;
    audioCodec->sample_rate = kAudioSampleRate;
    av_channel_layout_default(&audioCodec->ch_layout, 1);
    audioCodec->bit_rate = 128000;
    audioCodec->time_base = AVRational{1, kAudioSampleRate};
    audioCodec->flags |= AV_CODEC_FLAG_BITEXACT;
    if ((format->oformat->flags & AVFMT_GLOBALHEADER) != 0) audioCodec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    checkAv(avcodec_open2(audioCodec.get(), aac, nullptr), context + "opening the AAC encoder");
    audioStream = checkAllocated(avformat_new_stream(format.get(), nullptr), context + "adding the audio stream");
    checkAv(avcodec_parameters_from_context(audioStream->codecpar, audioCodec.get()),
            context + "copying the audio encoder's parameters to the stream");
    audioStream->time_base = audioCodec->time_base;
    audioFrame.reset(checkAllocated(av_frame_alloc(), context + "allocating an audio frame"));
    audioFrame->format = AV_SAMPLE_FMT_FLTP;
    audioFrame->sample_rate = kAudioSampleRate;
    checkAv(av_channel_layout_copy(&audioFrame->ch_layout, &audioCodec->ch_layout), context + "setting the channel layout");
    audioFrame->nb_samples = audioCodec->frame_size;
    checkAv(av_frame_get_buffer(audioFrame.get(), 0), context + "allocating audio frame buffers");
  }

  checkAv(avio_open(&format->pb, temporary.c_str(), AVIO_FLAG_WRITE), context + "opening " + temporary);
  AVDictionary* rawOptions = nullptr;
  int setResult = 0;
  // faststart rewrites the file at the trailer so moov precedes mdat.
  if (options.format == VideoFormat::Mp4 || options.format == VideoFormat::Mov) {
    setResult = av_dict_set(&rawOptions, "movflags", "+faststart", 0);
  }
  if (options.format == VideoFormat::Gif) setResult = av_dict_set(&rawOptions, "loop", "0", 0);  // 0: for ever
  DictionaryPtr muxerOptions(rawOptions);
  checkAv(setResult, context + "setting the muxer's options");
  // avformat_init_output replaces the dictionary with the options it did not use.
  rawOptions = muxerOptions.release();
  const int initResult = avformat_init_output(format.get(), &rawOptions);
  muxerOptions.reset(rawOptions);
  checkAv(initResult, context + "setting up the " + label + " muxer");
  if (av_dict_count(muxerOptions.get()) != 0) {
    throw std::runtime_error(context + "the " + label + " muxer ignored option '" +
                             av_dict_get(muxerOptions.get(), "", nullptr, AV_DICT_IGNORE_SUFFIX)->key + "'");
  }
  // After avformat_init_output, which under AVFMT_FLAG_BITEXACT drops any "encoder" tag (it would
  // otherwise hold libavformat's version): ours names the release, which is as stable as the bytes.
  if (!options.provenance.empty()) {
    checkAv(av_dict_set(&format->metadata, "encoder", options.provenance.software.c_str(), 0), context + "setting the encoder tag");
    checkAv(av_dict_set(&format->metadata, "comment", options.provenance.comment().c_str(), 0), context + "setting the comment tag");
  }
  checkAv(avformat_write_header(format.get(), nullptr), context + "writing the " + label + " header");

  frame.reset(checkAllocated(av_frame_alloc(), context + "allocating a frame"));
  frame->format = codec->pix_fmt;
  frame->width = options.width;
  frame->height = options.height;
  frame->color_primaries = codec->color_primaries;
  frame->color_trc = codec->color_trc;
  frame->colorspace = codec->colorspace;
  frame->color_range = codec->color_range;
  checkAv(av_frame_get_buffer(frame.get(), 0), context + "allocating frame buffers");
  packet.reset(checkAllocated(av_packet_alloc(), context + "allocating a packet"));
  if (yuv) {
    scaler = makeRgbaToYuvScaler(options.width, options.height, kRgbaToYuvScalerFlags, codec->pix_fmt);
  } else {
    palette = gifPalette();
  }
}

void EncoderSink::Encoder::encode(AVCodecContext& encoder, AVStream& target, const AVFrame* input, const char* what) {
  checkAv(avcodec_send_frame(&encoder, input),
          context + (input ? "sending a frame to " : "flushing ") + what);
  for (;;) {
    const int received = avcodec_receive_packet(&encoder, packet.get());
    if (received == AVERROR(EAGAIN) || received == AVERROR_EOF) return;
    checkAv(received, context + "receiving a packet from " + what);
    // Every video frame lasts one tick of 1/fps. libx264 leaves the duration 0 and FFmpeg 5.1's
    // muxer then guesses it from the stream's frame rate, which gives the same tick; saying it here
    // keeps the last frame's length (and so the file's) from resting on that guess. (The AAC
    // encoder sets its packets' durations itself.)
    if (&encoder == codec.get()) packet->duration = 1;
    av_packet_rescale_ts(packet.get(), encoder.time_base, target.time_base);
    packet->stream_index = target.index;
    checkAv(av_interleaved_write_frame(format.get(), packet.get()), context + "writing a packet");
  }
}

void EncoderSink::Encoder::encodeAudioBlock(int count) {
  checkAv(av_frame_make_writable(audioFrame.get()), context + "making the audio frame writable");
  audioFrame->nb_samples = count;
  std::copy_n(pending.begin(), count, reinterpret_cast<float*>(audioFrame->data[0]));
  pending.erase(pending.begin(), pending.begin() + count);
  audioFrame->pts = audioSamplesSent;
  audioSamplesSent += count;
  encode(*audioCodec, *audioStream, audioFrame.get(), "the AAC encoder");
}

EncoderSink::EncoderSink(std::filesystem::path destination, const VideoOptions& options)
    : destination_(std::move(destination)), options_(options) {
  validate(options_);
  // The encoders and the muxers report settings and statistics at "info" level; a command-line tool
  // prints its own summary, and every failure reaches the caller as an exception.
  av_log_set_level(AV_LOG_ERROR);
  encoder_ = std::make_unique<Encoder>(destination_, options_);
}

EncoderSink::~EncoderSink() = default;

std::uint64_t EncoderSink::workingMemory(std::uint64_t frameBytes) const {
  // Measured: the smallest address-space limit under which a 3 s, 960x540 clip is encoded, less
  // the renderer's and the queue's estimates, per RGBA byte of a frame: 6.4, 17.5, 31, 51, 62, 157
  // and 185 for ultrafast, veryfast, faster, medium, slow, veryslow and placebo (x264 0.164, one
  // thread); rounded up by a quarter, superfast, fast and slower taken between their neighbours.
  // More frames in flight (lookahead, references, B-frames) need more.
  constexpr std::array<std::uint64_t, kX264Presets.size()> kFramesOfMemory = {8, 12, 22, 39, 52, 64, 78, 132, 197, 232};
  // The other encoders were not measured so: VP9's realtime deadline looks ahead no frames and
  // keeps a few references, ProRes codes each frame alone, GIF compares with the frame before; 16,
  // 4 and 4 frames are generous estimates of that.
  switch (options_.format) {
    case VideoFormat::WebM: return 16 * frameBytes;
    case VideoFormat::Mov:
    case VideoFormat::Gif: return 4 * frameBytes;
    case VideoFormat::Mp4: break;
  }
  const auto preset = std::find(kX264Presets.begin(), kX264Presets.end(), options_.x264.preset);
  return kFramesOfMemory[static_cast<std::size_t>(preset - kX264Presets.begin())] * frameBytes;
}

void EncoderSink::push(const image::Image& frame) {
  if (finished_) throw std::logic_error(destination_.string() + ": push() after finish()");
  if (frame.width != options_.width || frame.height != options_.height ||
      frame.rgba.size() != static_cast<std::size_t>(frame.width) * frame.height * 4) {
    throw std::invalid_argument(destination_.string() + ": frame " + std::to_string(framesPushed_) + " is " +
                                std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                                ", the video is " + std::to_string(options_.width) + "x" +
                                std::to_string(options_.height));
  }
  Encoder& encoder = *encoder_;
  // The encoder may still hold a reference to the previous frame's buffers.
  checkAv(av_frame_make_writable(encoder.frame.get()), encoder.context + "making the frame writable");
  if (encoder.scaler) {
    convertRgbaToYuv(*encoder.scaler, frame, *encoder.frame);
  } else {
    quantizeForGif(frame, encoder.frame->data[0], encoder.frame->linesize[0]);
    std::memcpy(encoder.frame->data[1], encoder.palette.data(), sizeof encoder.palette);
  }
  encoder.frame->pts = framesPushed_;
  encoder.encode(*encoder.codec, *encoder.stream, encoder.frame.get(), encoder.container.encoder);
  ++framesPushed_;
}

void EncoderSink::pushAudio(std::span<const float> samples) {
  if (finished_) throw std::logic_error(destination_.string() + ": pushAudio() after finish()");
  Encoder& encoder = *encoder_;
  if (!encoder.audioCodec) throw std::logic_error(destination_.string() + ": audio pushed to a video without an audio track");
  encoder.pending.insert(encoder.pending.end(), samples.begin(), samples.end());
  const auto block = static_cast<std::size_t>(encoder.audioCodec->frame_size);
  while (encoder.pending.size() >= block) encoder.encodeAudioBlock(static_cast<int>(block));
}

void EncoderSink::finish() {
  if (finished_) throw std::logic_error(destination_.string() + ": finish() called twice");
  if (framesPushed_ == 0) throw std::runtime_error(destination_.string() + ": no frames to write");
  Encoder& encoder = *encoder_;
  encoder.encode(*encoder.codec, *encoder.stream, nullptr, encoder.container.encoder);
  if (encoder.audioCodec) {
    if (!encoder.pending.empty()) encoder.encodeAudioBlock(static_cast<int>(encoder.pending.size()));
    encoder.encode(*encoder.audioCodec, *encoder.audioStream, nullptr, "the AAC encoder");
  }
  checkAv(av_write_trailer(encoder.format.get()), encoder.context + "writing the " + encoder.container.label + " trailer");
  checkAv(avio_closep(&encoder.format->pb), encoder.context + "closing the file");
  if (options_.format == VideoFormat::Gif && !options_.provenance.empty()) {
    addGifComment(encoder.file.temporaryPath(), options_.provenance.comment());
  }
  encoder.file.commit();
  finished_ = true;
}

}  // namespace coinroll::video
