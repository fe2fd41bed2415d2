#include "video/scene_digest.h"

#include <cstdint>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <string_view>

#include "video/ffmpeg_handles.h"

namespace coinroll::video {

namespace {

// Bytes read from a PNG: its provenance sits right after the header (the tEXt chunks follow IHDR).
constexpr std::streamsize kHeadBytes = 64 * 1024;
constexpr std::string_view kPngSignature = "\x89PNG\r\n\x1a\n";
constexpr std::string_view kDigestKey = "coinroll-scene-digest";

std::uint32_t bigEndian(std::string_view bytes) {
  std::uint32_t value = 0;
  for (const char c : bytes.substr(0, 4)) value = value << 8 | static_cast<std::uint8_t>(c);
  return value;
}

// The PNG's tEXt chunk keyed coinroll-scene-digest, among the chunks before the pixels.
std::optional<std::string> pngDigest(std::string_view png) {
  for (std::size_t at = kPngSignature.size(); at + 8 <= png.size();) {
    const std::size_t length = bigEndian(png.substr(at, 4));
    const std::string_view type = png.substr(at + 4, 4);
    if (type == "IDAT" || type == "IEND" || at + 8 + length > png.size()) break;
    const std::string_view data = png.substr(at + 8, length);
    if (type == "tEXt" && data.substr(0, kDigestKey.size() + 1) == std::string(kDigestKey) + '\0') {
      return std::string(data.substr(kDigestKey.size() + 1));
    }
    at += 12 + length;  // length, type, data, CRC
  }
  return std::nullopt;
}

// A container's comment tag, through libavformat, which says nothing on stderr for a file it
// cannot read (a file of another kind under a video's name is an answer here, not an error).
std::optional<std::string> containerComment(const std::filesystem::path& path) {
  const int level = av_log_get_level();
  av_log_set_level(AV_LOG_QUIET);
  AVFormatContext* raw = nullptr;
  const int opened = avformat_open_input(&raw, path.c_str(), nullptr, nullptr);  // frees the context on failure
  av_log_set_level(level);
  if (opened < 0) return std::nullopt;
  const std::unique_ptr<AVFormatContext, detail::InputFormatDeleter> format(raw);
  const AVDictionaryEntry* comment = av_dict_get(format->metadata, "comment", nullptr, 0);
  if (comment == nullptr) return std::nullopt;
  return std::string(comment->value);
}

// The digest in Provenance::comment()'s text, "coinroll 0.1.0, scene fnv1a64:...", or none.
std::optional<std::string> sceneDigestInComment(std::string_view comment) {
  constexpr std::string_view kMarker = ", scene ";
  const std::size_t at = comment.rfind(kMarker);
  if (at == std::string_view::npos || comment.substr(0, 9) != "coinroll ") return std::nullopt;
  return std::string(comment.substr(at + kMarker.size()));
}

}  // namespace

std::optional<std::string> readSceneDigest(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(static_cast<std::size_t>(kHeadBytes), '\0');
  in.read(head.data(), kHeadBytes);
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.starts_with(kPngSignature)) return pngDigest(head);
  const std::optional<std::string> comment = containerComment(path);
  return comment ? sceneDigestInComment(*comment) : std::nullopt;
}

}  // namespace coinroll::video
