#include "video/mp4_sink.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "io/output_file.h"
#include "video/ffmpeg_handles.h"
#include "video/rgba_to_yuv.h"

extern "C" {
#include <libavutil/channel_layout.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
}

namespace coinroll::video {

using namespace detail;

namespace {

std::string mp4OptionError(const std::string& field, const std::string& rule, const std::string& value) {
  return "Mp4Options." + field + ": " + rule + ", got " + value;
}

}  // namespace

void validate(const Mp4Options& options) {
  auto requireEvenPositive = [](const char* field, int value) {
    if (value <= 0 || value % 2 != 0) {
      throw std::invalid_argument(mp4OptionError(field, "must be even and > 0 (yuv420p halves it)",
                                                 std::to_string(value)));
    }
  };
  requireEvenPositive("width", options.width);
  requireEvenPositive("height", options.height);
  if (options.fps <= 0) throw std::invalid_argument(mp4OptionError("fps", "must be > 0", std::to_string(options.fps)));
  const X264Options& x264 = options.x264;
  if (x264.crf < 0 || x264.crf > kMaxCrf) {
    throw std::invalid_argument(mp4OptionError("x264.crf", "must be in 0.." + std::to_string(kMaxCrf), std::to_string(x264.crf)));
  }
  if (std::find(kX264Presets.begin(), kX264Presets.end(), x264.preset) == kX264Presets.end()) {
    std::string presets;
    for (const std::string_view preset : kX264Presets) presets += (presets.empty() ? "" : ", ") + std::string(preset);
    throw std::invalid_argument(mp4OptionError("x264.preset", "must be an x264 preset (" + presets + ")", "'" + x264.preset + "'"));
  }
  if (x264.threads < 1 || x264.threads > kMaxX264Threads) {
    throw std::invalid_argument(
        mp4OptionError("x264.threads", "must be in 1.." + std::to_string(kMaxX264Threads), std::to_string(x264.threads)));
  }
}

struct Mp4Sink::Encoder {
  // Declared first so it is destroyed last, after the muxer has closed the temporary file.
  // ByPath: the muxer writes the file itself and rereads it for faststart, so a stream
  // destination (a pipe, /dev/stdout) gets the finished file copied to it by commit().
  io::OutputFile file;
  std::string context;  // "<destination>: " prefix for error messages
  OutputFormatPtr format;
  CodecContextPtr codec;
  AVStream* stream = nullptr;  // owned by `format`
  FramePtr frame;
  PacketPtr packet;
  ScalerPtr scaler;

  // The AAC track, when asked for. AAC codes fixed blocks of frame_size samples, so samples wait
  // in `pending` until a block is full; the last, shorter block goes out at finish().
  CodecContextPtr audioCodec;
  AVStream* audioStream = nullptr;  // owned by `format`
  FramePtr audioFrame;
  std::vector<float> pending;
  std::int64_t audioSamplesSent = 0;

  Encoder(const std::filesystem::path& destination, const Mp4Options& options);

  // Sends `frame` (or nullptr to drain) to an encoder and muxes every packet it returns.
  void encode(AVCodecContext& encoder, AVStream& target, const AVFrame* frame, const char* what);
  // Encodes `count` samples from the front of `pending`.
  void encodeAudioBlock(int count);
};

Mp4Sink::Encoder::Encoder(const std::filesystem::path& destination, const Mp4Options& options)
    : file(destination, "MP4", io::OutputFile::Access::ByPath), context(destination.string() + ": ") {
  const std::string temporary = file.temporaryPath().string();

  // The muxer is named, not guessed: the temporary name does not end in .mp4.
  AVFormatContext* rawFormat = nullptr;
  checkAv(avformat_alloc_output_context2(&rawFormat, nullptr, "mp4", temporary.c_str()),
          context + "creating the MP4 muxer");
  format.reset(rawFormat);
  // No encoder version string and no creation time: the same frames give the same bytes.
  format->flags |= AVFMT_FLAG_BITEXACT;

  const AVCodec* x264 = avcodec_find_encoder_by_name("libx264");
  if (x264 == nullptr) throw std::runtime_error(context + "this FFmpeg build has no libx264 encoder");
  codec.reset(checkAllocated(avcodec_alloc_context3(x264), context + "allocating the H.264 encoder"));
  codec->width = options.width;
  codec->height = options.height;
  codec->pix_fmt = AV_PIX_FMT_YUV420P;
  codec->time_base = AVRational{1, options.fps};
  codec->framerate = AVRational{options.fps, 1};
  codec->thread_count = options.x264.threads;
  codec->color_primaries = AVCOL_PRI_BT709;
  codec->color_trc = AVCOL_TRC_BT709;
  codec->colorspace = AVCOL_SPC_BT709;
  codec->color_range = AVCOL_RANGE_MPEG;
  codec->flags |= AV_CODEC_FLAG_BITEXACT;
  if ((format->oformat->flags & AVFMT_GLOBALHEADER) != 0) codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  checkAv(av_opt_set(codec->priv_data, "preset", options.x264.preset.c_str(), 0), context + "setting x264 preset");
  checkAv(av_opt_set_double(codec->priv_data, "crf", options.x264.crf, 0), context + "setting x264 crf");
  checkAv(avcodec_open2(codec.get(), x264, nullptr), context + "opening the libx264 encoder");

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
  // faststart rewrites the file at the trailer so moov precedes mdat.
  AVDictionary* rawOptions = nullptr;
  const int setResult = av_dict_set(&rawOptions, "movflags", "+faststart", 0);
  DictionaryPtr muxerOptions(rawOptions);
  checkAv(setResult, context + "setting movflags");
  // avformat_write_header replaces the dictionary with the options it did not use.
  rawOptions = muxerOptions.release();
  const int headerResult = avformat_write_header(format.get(), &rawOptions);
  muxerOptions.reset(rawOptions);
  checkAv(headerResult, context + "writing the MP4 header");
  if (av_dict_count(muxerOptions.get()) != 0) {
    throw std::runtime_error(context + "the MP4 muxer ignored option '" +
                             av_dict_get(muxerOptions.get(), "", nullptr, AV_DICT_IGNORE_SUFFIX)->key + "'");
  }

  frame.reset(checkAllocated(av_frame_alloc(), context + "allocating a frame"));
  frame->format = AV_PIX_FMT_YUV420P;
  frame->width = options.width;
  frame->height = options.height;
  frame->color_primaries = codec->color_primaries;
  frame->color_trc = codec->color_trc;
  frame->colorspace = codec->colorspace;
  frame->color_range = codec->color_range;
  checkAv(av_frame_get_buffer(frame.get(), 0), context + "allocating frame buffers");
  packet.reset(checkAllocated(av_packet_alloc(), context + "allocating a packet"));
  scaler = makeRgbaToYuvScaler(options.width, options.height, kRgbaToYuvScalerFlags);
}

void Mp4Sink::Encoder::encode(AVCodecContext& encoder, AVStream& target, const AVFrame* input, const char* what) {
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

void Mp4Sink::Encoder::encodeAudioBlock(int count) {
  checkAv(av_frame_make_writable(audioFrame.get()), context + "making the audio frame writable");
  audioFrame->nb_samples = count;
  std::copy_n(pending.begin(), count, reinterpret_cast<float*>(audioFrame->data[0]));
  pending.erase(pending.begin(), pending.begin() + count);
  audioFrame->pts = audioSamplesSent;
  audioSamplesSent += count;
  encode(*audioCodec, *audioStream, audioFrame.get(), "the AAC encoder");
}

Mp4Sink::Mp4Sink(std::filesystem::path destination, const Mp4Options& options)
    : destination_(std::move(destination)), options_(options) {
  validate(options_);
  // x264 and the muxer report settings and statistics at "info" level; a command-line tool
  // prints its own summary, and every failure reaches the caller as an exception.
  av_log_set_level(AV_LOG_ERROR);
  encoder_ = std::make_unique<Encoder>(destination_, options_);
}

Mp4Sink::~Mp4Sink() = default;

std::uint64_t Mp4Sink::workingMemory(std::uint64_t frameBytes) const {
  // Measured: the smallest address-space limit under which a 3 s, 960x540 clip is encoded, less
  // the renderer's and the queue's estimates, per RGBA byte of a frame: 6.4, 17.5, 31, 51, 62, 157
  // and 185 for ultrafast, veryfast, faster, medium, slow, veryslow and placebo (x264 0.164, one
  // thread); rounded up by a quarter, superfast, fast and slower taken between their neighbours.
  // More frames in flight (lookahead, references, B-frames) need more.
  constexpr std::array<std::uint64_t, kX264Presets.size()> kFramesOfMemory = {8, 12, 22, 39, 52, 64, 78, 132, 197, 232};
  const auto preset = std::find(kX264Presets.begin(), kX264Presets.end(), options_.x264.preset);
  return kFramesOfMemory[static_cast<std::size_t>(preset - kX264Presets.begin())] * frameBytes;
}

void Mp4Sink::push(const image::Image& frame) {
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
  convertRgbaToYuv(*encoder.scaler, frame, *encoder.frame);
  encoder.frame->pts = framesPushed_;
  encoder.encode(*encoder.codec, *encoder.stream, encoder.frame.get(), "libx264");
  ++framesPushed_;
}

void Mp4Sink::pushAudio(std::span<const float> samples) {
  if (finished_) throw std::logic_error(destination_.string() + ": pushAudio() after finish()");
  Encoder& encoder = *encoder_;
  if (!encoder.audioCodec) throw std::logic_error(destination_.string() + ": audio pushed to a video without an audio track");
  encoder.pending.insert(encoder.pending.end(), samples.begin(), samples.end());
  const auto block = static_cast<std::size_t>(encoder.audioCodec->frame_size);
  while (encoder.pending.size() >= block) encoder.encodeAudioBlock(static_cast<int>(block));
}

void Mp4Sink::finish() {
  if (finished_) throw std::logic_error(destination_.string() + ": finish() called twice");
  if (framesPushed_ == 0) throw std::runtime_error(destination_.string() + ": no frames to write");
  Encoder& encoder = *encoder_;
  encoder.encode(*encoder.codec, *encoder.stream, nullptr, "libx264");
  if (encoder.audioCodec) {
    if (!encoder.pending.empty()) encoder.encodeAudioBlock(static_cast<int>(encoder.pending.size()));
    encoder.encode(*encoder.audioCodec, *encoder.audioStream, nullptr, "the AAC encoder");
  }
  checkAv(av_write_trailer(encoder.format.get()), encoder.context + "writing the MP4 trailer");
  checkAv(avio_closep(&encoder.format->pb), encoder.context + "closing the file");
  encoder.file.commit();
  finished_ = true;
}

}  // namespace coinroll::video
