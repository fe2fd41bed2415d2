#include "video_probe.h"

#include <array>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "video/ffmpeg_handles.h"

extern "C" {
#include <libavutil/pixdesc.h>
}

namespace coinroll::video {

using namespace detail;

namespace {

std::string nameOr(const char* name, const char* fallback) { return name != nullptr ? name : fallback; }

InputFormatPtr openInput(const std::filesystem::path& path) {
  AVFormatContext* raw = nullptr;
  // On failure avformat_open_input frees the context itself.
  checkAv(avformat_open_input(&raw, path.c_str(), nullptr, nullptr), path.string() + ": opening");
  InputFormatPtr format(raw);
  checkAv(avformat_find_stream_info(format.get(), nullptr), path.string() + ": reading stream information");
  return format;
}

int findVideoStream(AVFormatContext& format, const std::filesystem::path& path, const AVCodec** decoder) {
  return checkAv(av_find_best_stream(&format, AVMEDIA_TYPE_VIDEO, -1, -1, decoder, 0),
                 path.string() + ": finding a video stream");
}

std::uint64_t readBigEndian(const unsigned char* bytes, int count) {
  std::uint64_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | bytes[i];
  return value;
}

// Walks the top-level boxes (ISO/IEC 14496-12 section 4.2: 32-bit size, 4-character type, size 1
// means a 64-bit size follows, size 0 means "to the end of the file").
bool moovPrecedesMdat(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::uint64_t offset = 0;
  for (;;) {
    std::array<unsigned char, 16> header{};
    file.seekg(static_cast<std::streamoff>(offset));
    if (!file.read(reinterpret_cast<char*>(header.data()), 8)) return false;
    const std::string type(reinterpret_cast<const char*>(header.data() + 4), 4);
    if (type == "moov") return true;
    if (type == "mdat") return false;
    std::uint64_t size = readBigEndian(header.data(), 4);
    if (size == 1) {
      if (!file.read(reinterpret_cast<char*>(header.data() + 8), 8)) return false;
      size = readBigEndian(header.data() + 8, 8);
    }
    if (size < 8) return false;  // size 0 (the rest of the file) or malformed: no box follows
    offset += size;
  }
}

}  // namespace

std::vector<int> gifFrameDelays(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  const std::string gif{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  const auto fail = [&](const std::string& what) { return std::runtime_error(path.string() + ": " + what); };
  const auto byte = [&](std::size_t at) {
    if (at >= gif.size()) throw fail("cut short at byte " + std::to_string(at));
    return static_cast<std::uint8_t>(gif[at]);
  };
  if (gif.compare(0, 6, "GIF89a") != 0) throw fail("not a GIF89a stream");
  // A packed byte's colour table: 3 * 2^(n + 1) bytes when its top bit is set (GIF89a section 18).
  const auto colourTable = [](std::uint8_t packed) -> std::size_t {
    return (packed & 0x80) != 0 ? 3u << ((packed & 7) + 1) : 0;
  };
  // Data sub-blocks, each a length byte then its bytes, up to a zero length.
  const auto afterSubBlocks = [&](std::size_t at) {
    while (byte(at) != 0) at += 1 + byte(at);
    return at + 1;
  };
  std::vector<int> delays;
  std::size_t at = 13 + colourTable(byte(10));  // header and Logical Screen Descriptor
  for (;;) {
    switch (byte(at)) {
      case 0x21:  // an extension: the Graphic Control one holds the next frame's delay, little endian
        if (byte(at + 1) == 0xF9) delays.push_back(byte(at + 4) | (byte(at + 5) << 8));
        at = afterSubBlocks(at + 2);
        break;
      case 0x2C:  // an image: its descriptor, its local colour table, the LZW code size, the data
        at = afterSubBlocks(at + 10 + colourTable(byte(at + 9)) + 1);
        break;
      case 0x3B:  // the trailer
        return delays;
      default: throw fail("no GIF block at byte " + std::to_string(at));
    }
  }
}

VideoInfo readVideoInfo(const std::filesystem::path& path) {
  InputFormatPtr format = openInput(path);
  const int streamIndex = findVideoStream(*format, path, nullptr);
  const AVStream& stream = *format->streams[streamIndex];
  const AVCodecParameters& parameters = *stream.codecpar;

  VideoInfo info;
  info.codecName = avcodec_get_name(parameters.codec_id);
  info.pixelFormat = nameOr(av_get_pix_fmt_name(static_cast<AVPixelFormat>(parameters.format)), "none");
  info.width = parameters.width;
  info.height = parameters.height;
  info.colorPrimaries = nameOr(av_color_primaries_name(parameters.color_primaries), "unknown");
  info.colorTransfer = nameOr(av_color_transfer_name(parameters.color_trc), "unknown");
  info.colorSpace = nameOr(av_color_space_name(parameters.color_space), "unknown");
  info.colorRange = nameOr(av_color_range_name(parameters.color_range), "unknown");
  info.fps = stream.avg_frame_rate.den != 0 ? av_q2d(stream.avg_frame_rate) : 0.0;
  info.durationSeconds = stream.duration != AV_NOPTS_VALUE
                             ? static_cast<double>(stream.duration) * av_q2d(stream.time_base)
                             : static_cast<double>(format->duration) / AV_TIME_BASE;

  PacketPtr packet(checkAllocated(av_packet_alloc(), path.string() + ": allocating a packet"));
  for (;;) {
    const int result = av_read_frame(format.get(), packet.get());
    if (result == AVERROR_EOF) break;
    checkAv(result, path.string() + ": reading a packet");
    if (packet->stream_index == streamIndex) ++info.frameCount;
    av_packet_unref(packet.get());
  }
  info.moovBeforeMdat = moovPrecedesMdat(path);
  const AVPixFmtDescriptor* descriptor = av_pix_fmt_desc_get(static_cast<AVPixelFormat>(parameters.format));
  const AVDictionaryEntry* alphaMode = av_dict_get(stream.metadata, "alpha_mode", nullptr, 0);
  info.alpha = (descriptor != nullptr && (descriptor->flags & AV_PIX_FMT_FLAG_ALPHA) != 0) ||
               (alphaMode != nullptr && std::string(alphaMode->value) == "1");
  for (const AVDictionaryEntry* tag = nullptr; (tag = av_dict_get(format->metadata, "", tag, AV_DICT_IGNORE_SUFFIX));) {
    info.tags[tag->key] = tag->value;
  }
  return info;
}

image::Image decodeFrame(const std::filesystem::path& path, std::int64_t index) {
  InputFormatPtr format = openInput(path);
  const AVCodec* decoder = nullptr;
  const int streamIndex = findVideoStream(*format, path, &decoder);
  // FFmpeg's own VP9 decoder drops the alpha that WebM carries beside the picture; libvpx's keeps it.
  if (format->streams[streamIndex]->codecpar->codec_id == AV_CODEC_ID_VP9) {
    if (const AVCodec* libvpx = avcodec_find_decoder_by_name("libvpx-vp9")) decoder = libvpx;
  }
  CodecContextPtr codec(checkAllocated(avcodec_alloc_context3(decoder), path.string() + ": allocating a decoder"));
  checkAv(avcodec_parameters_to_context(codec.get(), format->streams[streamIndex]->codecpar),
          path.string() + ": configuring the decoder");
  checkAv(avcodec_open2(codec.get(), decoder, nullptr), path.string() + ": opening the decoder");

  PacketPtr packet(checkAllocated(av_packet_alloc(), path.string() + ": allocating a packet"));
  FramePtr frame(checkAllocated(av_frame_alloc(), path.string() + ": allocating a frame"));
  std::int64_t decoded = 0;
  bool draining = false;
  for (;;) {
    // Feed one packet (or the end-of-stream flush), then take every frame that is ready.
    if (!draining) {
      const int result = av_read_frame(format.get(), packet.get());
      if (result == AVERROR_EOF) {
        draining = true;
        checkAv(avcodec_send_packet(codec.get(), nullptr), path.string() + ": flushing the decoder");
      } else {
        checkAv(result, path.string() + ": reading a packet");
        const bool isVideo = packet->stream_index == streamIndex;
        const int sent = isVideo ? avcodec_send_packet(codec.get(), packet.get()) : 0;
        av_packet_unref(packet.get());
        checkAv(sent, path.string() + ": decoding a packet");
      }
    }
    for (;;) {
      const int received = avcodec_receive_frame(codec.get(), frame.get());
      if (received == AVERROR(EAGAIN)) break;
      if (received == AVERROR_EOF) {
        throw std::runtime_error(path.string() + ": has " + std::to_string(decoded) + " frames, frame " +
                                 std::to_string(index) + " requested");
      }
      checkAv(received, path.string() + ": receiving a decoded frame");
      if (decoded++ != index) continue;

      ScalerPtr scaler(sws_getContext(frame->width, frame->height, static_cast<AVPixelFormat>(frame->format),
                                      frame->width, frame->height, AV_PIX_FMT_RGBA,
                                      SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, nullptr, nullptr, nullptr));
      if (!scaler) throw std::runtime_error(path.string() + ": cannot convert its pixel format to RGBA");
      const int* matrix = sws_getCoefficients(frame->colorspace);
      setScalerColorDetails(*scaler, matrix, frame->color_range == AVCOL_RANGE_JPEG, matrix, true,
                            path.string() + ": setting the decoded frame's colour space");
      image::Image rgba(frame->width, frame->height);
      std::uint8_t* const destinationPlanes[] = {rgba.rgba.data()};
      const int destinationStrides[] = {rgba.width * 4};
      checkAv(sws_scale(scaler.get(), frame->data, frame->linesize, 0, frame->height, destinationPlanes,
                        destinationStrides),
              path.string() + ": converting a decoded frame to RGBA");
      return rgba;
    }
  }
}

DecodedAudio decodeAudio(const std::filesystem::path& path) {
  InputFormatPtr format = openInput(path);
  const AVCodec* decoder = nullptr;
  const int streamIndex = checkAv(av_find_best_stream(format.get(), AVMEDIA_TYPE_AUDIO, -1, -1, &decoder, 0),
                                  path.string() + ": finding an audio stream");
  const AVStream& stream = *format->streams[streamIndex];
  CodecContextPtr codec(checkAllocated(avcodec_alloc_context3(decoder), path.string() + ": allocating a decoder"));
  checkAv(avcodec_parameters_to_context(codec.get(), stream.codecpar), path.string() + ": configuring the decoder");
  checkAv(avcodec_open2(codec.get(), decoder, nullptr), path.string() + ": opening the audio decoder");

  DecodedAudio audio;
  audio.codecName = avcodec_get_name(stream.codecpar->codec_id);
  audio.sampleRate = stream.codecpar->sample_rate;
  audio.durationSeconds = static_cast<double>(stream.duration) * av_q2d(stream.time_base);
  PacketPtr packet(checkAllocated(av_packet_alloc(), path.string() + ": allocating a packet"));
  FramePtr frame(checkAllocated(av_frame_alloc(), path.string() + ": allocating a frame"));
  const auto drain = [&] {
    for (;;) {
      const int received = avcodec_receive_frame(codec.get(), frame.get());
      if (received == AVERROR(EAGAIN) || received == AVERROR_EOF) return;
      checkAv(received, path.string() + ": decoding audio");
      if (frame->format != AV_SAMPLE_FMT_FLTP && frame->format != AV_SAMPLE_FMT_FLT) {
        throw std::runtime_error(path.string() + ": audio decodes to a sample format other than float");
      }
      const auto* first = reinterpret_cast<const float*>(frame->data[0]);
      const int stride = frame->format == AV_SAMPLE_FMT_FLT ? frame->ch_layout.nb_channels : 1;
      for (int i = 0; i < frame->nb_samples; ++i) audio.samples.push_back(first[i * stride]);
    }
  };
  while (av_read_frame(format.get(), packet.get()) >= 0) {
    if (packet->stream_index == streamIndex) {
      checkAv(avcodec_send_packet(codec.get(), packet.get()), path.string() + ": sending an audio packet");
      drain();
    }
    av_packet_unref(packet.get());
  }
  checkAv(avcodec_send_packet(codec.get(), nullptr), path.string() + ": flushing the audio decoder");
  drain();
  return audio;
}

}  // namespace coinroll::video
