#include "video/encoder_sink.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "io/output_file.h"
#include "video/ffmpeg_handles.h"
#include "video/gif_palette.h"
#include "video/rgba_to_yuv.h"
#include "video/video_kinds.h"

extern "C" {
#include <libavutil/channel_layout.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libavutil/pixdesc.h>
}

namespace coinroll::video {

using namespace detail;

namespace {

std::string videoOptionError(const std::string& field, const std::string& rule, const std::string& value) {
  return "VideoOptions." + field + ": " + rule + ", got " + value;
}

const AVPixFmtDescriptor& pixelFormatNamed(std::string_view name) {
  const AVPixFmtDescriptor* descriptor = av_pix_fmt_desc_get(av_get_pix_fmt(std::string(name).c_str()));
  if (descriptor == nullptr)
    throw std::logic_error("video_kinds.cpp names pixel format '" + std::string(name) + "', unknown to libav");
  return *descriptor;
}

AVPixelFormat pixelFormatOf(const VideoKind& kind, bool alpha) {
  return av_pix_fmt_desc_get_id(&pixelFormatNamed(alpha ? kind.alphaPixelFormat : kind.pixelFormat));
}

}  // namespace

void validate(const VideoOptions& options) {
  const VideoKind& kind = videoKind(options.format);
  const std::string label(kind.label);
  // Subsampled chroma (4:2:0 halves both sides) needs the sides it halves to be even.
  const AVPixFmtDescriptor& pixels = pixelFormatNamed(kind.pixelFormat);
  auto requireSide = [&](const char* field, int value, int chromaShift) {
    const bool even = chromaShift > 0;
    if (value <= 0 || (even && value % 2 != 0)) {
      throw std::invalid_argument(videoOptionError(
          field, even ? "must be even and > 0 (4:2:0 chroma halves it)" : "must be > 0", std::to_string(value)));
    }
  };
  requireSide("width", options.width, pixels.log2_chroma_w);
  requireSide("height", options.height, pixels.log2_chroma_h);
  if (options.fps <= 0)
    throw std::invalid_argument(videoOptionError("fps", "must be > 0", std::to_string(options.fps)));
  const X264Options& x264 = options.x264;
  if (x264.crf < 0 || x264.crf > kMaxCrf) {
    throw std::invalid_argument(
        videoOptionError("x264.crf", "must be in 0.." + std::to_string(kMaxCrf), std::to_string(x264.crf)));
  }
  if (std::find(kX264Presets.begin(), kX264Presets.end(), x264.preset) == kX264Presets.end()) {
    std::string presets;
    for (const std::string_view preset : kX264Presets) presets += (presets.empty() ? "" : ", ") + std::string(preset);
    throw std::invalid_argument(
        videoOptionError("x264.preset", "must be an x264 preset (" + presets + ")", "'" + x264.preset + "'"));
  }
  if (x264.threads < 1 || x264.threads > kMaxX264Threads) {
    throw std::invalid_argument(videoOptionError("x264.threads", "must be in 1.." + std::to_string(kMaxX264Threads),
                                                 std::to_string(x264.threads)));
  }
  if (options.alpha && !kind.keepsAlpha()) {
    throw std::invalid_argument(videoOptionError("alpha", label + " has no alpha channel", "true"));
  }
  if (options.audio && !kind.audio) {
    throw std::invalid_argument(videoOptionError("audio", label + " gets no sound track", "true"));
  }
  if (!kind.carriesFps(options.fps)) {
    throw std::invalid_argument(videoOptionError(
        "fps",
        label + " plays at most " + std::to_string(kind.maxFps) + " fps (" + std::string(kind.maxFpsReason) + ")",
        std::to_string(options.fps)));
  }
}

// One encoder and the muxer's stream it feeds: the pictures', and the sound's when there is one.
struct EncodedStream {
  std::string encoderName;  // in messages: "the libx264 encoder"
  CodecContextPtr codec;
  AVStream* stream = nullptr;  // owned by the muxer
  FramePtr frame;              // the next input, refilled for each
};

struct EncoderSink::Encoder {
  // Declared first so it is destroyed last, after the muxer has closed the temporary file.
  // ByPath: the muxer writes the file itself and rereads it for faststart, so a stream
  // destination (a pipe, /dev/stdout) gets the finished file copied to it by commit().
  io::OutputFile file;
  std::string context;  // "<destination>: " prefix for error messages
  const VideoKind& kind;
  OutputFormatPtr format;
  EncodedStream video;
  EncodedStream audio;  // without a codec when there is no sound track
  PacketPtr packet;
  ScalerPtr scaler;                          // RGBA to the YUV formats; none for a palette
  std::array<std::uint32_t, 256> palette{};  // GIF's (gifPalette()), copied into every frame

  // AAC codes fixed blocks of frame_size samples, so samples wait in `pending` until a block is
  // full; the last, shorter block goes out at finish().
  std::vector<float> pending;
  std::int64_t audioSamplesSent = 0;

  Encoder(const std::filesystem::path& destination, const VideoOptions& options, io::OutputGroup* group);

  // Opens `encoder` (named `name` in messages), set up by `configure`, and adds its stream, the
  // `medium`'s, to the muxer.
  EncodedStream openStream(const AVCodec* encoder, const std::string& name, const char* medium,
                           const std::function<void(AVCodecContext&)>& configure);
  // Sends `input` (or nullptr to drain) to the stream's encoder and muxes every packet it returns.
  void encode(EncodedStream& target, const AVFrame* input);
  // Encodes `count` samples from the front of `pending`.
  void encodeAudioBlock(int count);
};

EncodedStream EncoderSink::Encoder::openStream(const AVCodec* encoder, const std::string& name, const char* medium,
                                               const std::function<void(AVCodecContext&)>& configure) {
  if (encoder == nullptr) throw std::runtime_error(context + "this FFmpeg build has no " + name + " encoder");
  EncodedStream opened;
  opened.encoderName = "the " + name + " encoder";
  opened.codec.reset(checkAllocated(avcodec_alloc_context3(encoder), context + "allocating " + opened.encoderName));
  configure(*opened.codec);
  opened.codec->flags |= AV_CODEC_FLAG_BITEXACT;
  if ((format->oformat->flags & AVFMT_GLOBALHEADER) != 0) opened.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  checkAv(avcodec_open2(opened.codec.get(), encoder, nullptr), context + "opening " + opened.encoderName);
  opened.stream =
      checkAllocated(avformat_new_stream(format.get(), nullptr), context + "adding the " + medium + " stream");
  checkAv(avcodec_parameters_from_context(opened.stream->codecpar, opened.codec.get()),
          context + "copying the " + medium + " encoder's parameters to the stream");
  opened.stream->time_base = opened.codec->time_base;  // a hint; the muxer may choose a finer one
  return opened;
}

EncoderSink::Encoder::Encoder(const std::filesystem::path& destination, const VideoOptions& options,
                              io::OutputGroup* group)
    : file(destination, std::string(videoKind(options.format).label), io::OutputFile::Access::ByPath, group),
      context(destination.string() + ": "),
      kind(videoKind(options.format)) {
  const std::string temporary = file.temporaryPath().string();
  const std::string label(kind.label);

  // The muxer is named, not guessed: the temporary name has no extension.
  AVFormatContext* rawFormat = nullptr;
  checkAv(avformat_alloc_output_context2(&rawFormat, nullptr, std::string(kind.muxer).c_str(), temporary.c_str()),
          context + "creating the " + label + " muxer");
  format.reset(rawFormat);
  // No encoder version string, no creation time, no random segment id: the same frames give the same bytes.
  format->flags |= AVFMT_FLAG_BITEXACT;

  const AVPixelFormat pixelFormat = pixelFormatOf(kind, options.alpha);
  const bool paletted = (av_pix_fmt_desc_get(pixelFormat)->flags & AV_PIX_FMT_FLAG_PAL) != 0;
  const std::string encoderName(kind.encoder);
  video =
      openStream(avcodec_find_encoder_by_name(encoderName.c_str()), encoderName, "video", [&](AVCodecContext& codec) {
        codec.width = options.width;
        codec.height = options.height;
        codec.pix_fmt = pixelFormat;
        codec.time_base = AVRational{1, options.fps};
        codec.framerate = AVRational{options.fps, 1};
        if (!paletted) {
          codec.color_primaries = AVCOL_PRI_BT709;
          codec.color_trc = AVCOL_TRC_BT709;
          codec.colorspace = AVCOL_SPC_BT709;
          codec.color_range = AVCOL_RANGE_MPEG;
        }
        for (const auto& [name, value] : kind.encoderOptions(options)) {
          checkAv(av_opt_set(&codec, name.c_str(), value.c_str(), AV_OPT_SEARCH_CHILDREN),
                  context + "setting " + encoderName + "'s option " + name + " to " + value);
        }
      });
  video.stream->avg_frame_rate = video.codec->framerate;

  if (options.audio) {
    audio = openStream(avcodec_find_encoder(AV_CODEC_ID_AAC), "AAC", "audio", [](AVCodecContext& codec) {
      codec.sample_fmt = AV_SAMPLE_FMT_FLTP;
      codec.sample_rate = kAudioSampleRate;
      av_channel_layout_default(&codec.ch_layout, 1);
      codec.bit_rate = 128000;
      codec.time_base = AVRational{1, kAudioSampleRate};
    });
    audio.frame.reset(checkAllocated(av_frame_alloc(), context + "allocating an audio frame"));
    audio.frame->format = AV_SAMPLE_FMT_FLTP;
    audio.frame->sample_rate = kAudioSampleRate;
    checkAv(av_channel_layout_copy(&audio.frame->ch_layout, &audio.codec->ch_layout),
            context + "setting the channel layout");
    audio.frame->nb_samples = audio.codec->frame_size;
    checkAv(av_frame_get_buffer(audio.frame.get(), 0), context + "allocating audio frame buffers");
  }

  checkAv(avio_open(&format->pb, temporary.c_str(), AVIO_FLAG_WRITE), context + "opening " + temporary);
  LibavOptions muxerSettings;
  // faststart rewrites the file at the trailer so moov precedes mdat.
  if (kind.indexFirst) muxerSettings.emplace_back("movflags", "+faststart");
  if (kind.loops) muxerSettings.emplace_back("loop", "0");  // 0: for ever
  DictionaryPtr muxerOptions;
  for (const auto& [name, value] : muxerSettings) {
    AVDictionary* rawOptions = muxerOptions.release();
    const int setResult = av_dict_set(&rawOptions, name.c_str(), value.c_str(), 0);
    muxerOptions.reset(rawOptions);
    checkAv(setResult, context + "setting the muxer's options");
  }
  // avformat_init_output replaces the dictionary with the options it did not use.
  AVDictionary* rawOptions = muxerOptions.release();
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
    checkAv(av_dict_set(&format->metadata, "encoder", options.provenance.software.c_str(), 0),
            context + "setting the encoder tag");
    checkAv(av_dict_set(&format->metadata, "comment", options.provenance.comment().c_str(), 0),
            context + "setting the comment tag");
  }
  checkAv(avformat_write_header(format.get(), nullptr), context + "writing the " + label + " header");

  const AVCodecContext& codec = *video.codec;
  video.frame.reset(checkAllocated(av_frame_alloc(), context + "allocating a frame"));
  video.frame->format = codec.pix_fmt;
  video.frame->width = options.width;
  video.frame->height = options.height;
  video.frame->color_primaries = codec.color_primaries;
  video.frame->color_trc = codec.color_trc;
  video.frame->colorspace = codec.colorspace;
  video.frame->color_range = codec.color_range;
  checkAv(av_frame_get_buffer(video.frame.get(), 0), context + "allocating frame buffers");
  packet.reset(checkAllocated(av_packet_alloc(), context + "allocating a packet"));
  if (paletted) {
    palette = gifPalette();
  } else {
    scaler = makeRgbaToYuvScaler(options.width, options.height, kRgbaToYuvScalerFlags, codec.pix_fmt);
  }
}

void EncoderSink::Encoder::encode(EncodedStream& target, const AVFrame* input) {
  AVCodecContext& encoder = *target.codec;
  checkAv(avcodec_send_frame(&encoder, input),
          context + (input ? "sending a frame to " : "flushing ") + target.encoderName);
  for (;;) {
    const int received = avcodec_receive_packet(&encoder, packet.get());
    if (received == AVERROR(EAGAIN) || received == AVERROR_EOF) return;
    checkAv(received, context + "receiving a packet from " + target.encoderName);
    // Every video frame lasts one tick of 1/fps. libx264 leaves the duration 0 and FFmpeg 5.1's
    // muxer then guesses it from the stream's frame rate, which gives the same tick; saying it here
    // keeps the last frame's length (and so the file's) from resting on that guess. (The AAC
    // encoder sets its packets' durations itself.)
    if (&target == &video) packet->duration = 1;
    av_packet_rescale_ts(packet.get(), encoder.time_base, target.stream->time_base);
    packet->stream_index = target.stream->index;
    checkAv(av_interleaved_write_frame(format.get(), packet.get()), context + "writing a packet");
  }
}

void EncoderSink::Encoder::encodeAudioBlock(int count) {
  checkAv(av_frame_make_writable(audio.frame.get()), context + "making the audio frame writable");
  audio.frame->nb_samples = count;
  std::copy_n(pending.begin(), count, reinterpret_cast<float*>(audio.frame->data[0]));
  pending.erase(pending.begin(), pending.begin() + count);
  audio.frame->pts = audioSamplesSent;
  audioSamplesSent += count;
  encode(audio, audio.frame.get());
}

EncoderSink::EncoderSink(std::filesystem::path destination, const VideoOptions& options, io::OutputGroup* group)
    : destination_(std::move(destination)), options_(options) {
  validate(options_);
  // The encoders and the muxers report settings and statistics at "info" level; a command-line tool
  // prints its own summary, and every failure reaches the caller as an exception.
  av_log_set_level(AV_LOG_ERROR);
  encoder_ = std::make_unique<Encoder>(destination_, options_, group);
}

EncoderSink::~EncoderSink() = default;

std::uint64_t EncoderSink::workingMemory(std::uint64_t frameBytes) const {
  return videoKind(options_.format).framesInFlight(options_) * frameBytes;
}

void EncoderSink::push(const image::Image& frame) {
  if (finished_) throw std::logic_error(destination_.string() + ": push() after finish()");
  if (frame.width != options_.width || frame.height != options_.height ||
      frame.rgba.size() != static_cast<std::size_t>(frame.width) * frame.height * 4) {
    throw std::invalid_argument(destination_.string() + ": frame " + std::to_string(framesPushed_) + " is " +
                                std::to_string(frame.width) + "x" + std::to_string(frame.height) + ", the video is " +
                                std::to_string(options_.width) + "x" + std::to_string(options_.height));
  }
  Encoder& encoder = *encoder_;
  AVFrame& picture = *encoder.video.frame;
  // The encoder may still hold a reference to the previous frame's buffers.
  checkAv(av_frame_make_writable(&picture), encoder.context + "making the frame writable");
  if (encoder.scaler) {
    convertRgbaToYuv(*encoder.scaler, frame, picture);
  } else {
    quantizeForGif(frame, picture.data[0], picture.linesize[0]);
    std::memcpy(picture.data[1], encoder.palette.data(), sizeof encoder.palette);
  }
  picture.pts = framesPushed_;
  encoder.encode(encoder.video, &picture);
  ++framesPushed_;
}

void EncoderSink::pushAudio(std::span<const float> samples) {
  if (finished_) throw std::logic_error(destination_.string() + ": pushAudio() after finish()");
  Encoder& encoder = *encoder_;
  if (!encoder.audio.codec)
    throw std::logic_error(destination_.string() + ": audio pushed to a video without an audio track");
  encoder.pending.insert(encoder.pending.end(), samples.begin(), samples.end());
  const auto block = static_cast<std::size_t>(encoder.audio.codec->frame_size);
  while (encoder.pending.size() >= block) encoder.encodeAudioBlock(static_cast<int>(block));
}

void EncoderSink::finish() {
  if (finished_) throw std::logic_error(destination_.string() + ": finish() called twice");
  if (framesPushed_ == 0) throw std::runtime_error(destination_.string() + ": no frames to write");
  Encoder& encoder = *encoder_;
  const VideoKind& kind = encoder.kind;
  encoder.encode(encoder.video, nullptr);
  if (encoder.audio.codec) {
    if (!encoder.pending.empty()) encoder.encodeAudioBlock(static_cast<int>(encoder.pending.size()));
    encoder.encode(encoder.audio, nullptr);
  }
  if (!kind.lastFrameOption.empty()) {
    // The last frame ends where the clip does, so its length is the rest of the clip: the frames'
    // lengths then add up to the clip's, each frame ending where its own time does.
    const AVRational tick = encoder.video.codec->time_base, muxed = encoder.video.stream->time_base;
    const std::int64_t length = av_rescale_q(framesPushed_, tick, muxed) - av_rescale_q(framesPushed_ - 1, tick, muxed);
    const std::string option(kind.lastFrameOption);
    checkAv(av_opt_set_int(encoder.format->priv_data, option.c_str(), length, 0),
            encoder.context + "setting the muxer's option " + option);
  }
  checkAv(av_write_trailer(encoder.format.get()),
          encoder.context + "writing the " + std::string(kind.label) + " trailer");
  checkAv(avio_closep(&encoder.format->pb), encoder.context + "closing the file");
  if (kind.addComment != nullptr && !options_.provenance.empty()) {
    kind.addComment(encoder.file.temporaryPath(), options_.provenance.comment());
  }
  encoder.file.commit();
  finished_ = true;
}

}  // namespace coinroll::video
