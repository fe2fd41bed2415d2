#include "video/gif_comment.h"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace coinroll::video {

namespace {

constexpr std::size_t kScreenDescriptorEnd = 13;  // "GIF89a", then 7 bytes of Logical Screen Descriptor
constexpr unsigned char kExtension = 0x21, kCommentLabel = 0xFE;
constexpr std::size_t kMaxSubBlock = 255;

// Where the frames' part of the stream begins: after the header, the descriptor and the Global
// Color Table, whose size the descriptor's packed byte gives (3 * 2^(n + 1) bytes when present).
std::size_t afterGlobalColorTable(std::string_view gif) {
  if (gif.size() < kScreenDescriptorEnd || gif.substr(0, 6) != "GIF89a") {
    throw std::invalid_argument("not a GIF89a stream");
  }
  const auto packed = static_cast<std::uint8_t>(gif[10]);
  const std::size_t table = (packed & 0x80) != 0 ? 3u << ((packed & 0x07) + 1) : 0;
  if (gif.size() < kScreenDescriptorEnd + table) throw std::invalid_argument("GIF cut short in its colour table");
  return kScreenDescriptorEnd + table;
}

}  // namespace

std::string withGifComment(std::string_view gif, std::string_view comment) {
  const std::size_t at = afterGlobalColorTable(gif);
  std::string block{static_cast<char>(kExtension), static_cast<char>(kCommentLabel)};
  for (std::size_t from = 0; from < comment.size(); from += kMaxSubBlock) {
    const std::string_view part = comment.substr(from, kMaxSubBlock);
    block += static_cast<char>(part.size());
    block += part;
  }
  block += '\0';  // block terminator
  std::string out(gif.substr(0, at));
  out += block;
  out += gif.substr(at);
  return out;
}

std::string gifComment(std::string_view gif) {
  // Blocks after the colour table are extensions (0x21, label, sub-blocks) until the first image;
  // the comment is among them.
  std::size_t at = afterGlobalColorTable(gif);
  while (at + 1 < gif.size() && static_cast<std::uint8_t>(gif[at]) == kExtension) {
    const bool isComment = static_cast<std::uint8_t>(gif[at + 1]) == kCommentLabel;
    std::string text;
    at += 2;
    while (at < gif.size() && gif[at] != '\0') {
      const auto length = static_cast<std::uint8_t>(gif[at]);
      text += gif.substr(at + 1, length);
      at += 1 + length;
    }
    if (isComment) return text;
    ++at;  // the terminator
  }
  return {};
}

void addGifComment(const std::filesystem::path& path, std::string_view comment) {
  std::string gif;
  {
    std::ifstream in(path, std::ios::binary);
    gif.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) throw std::runtime_error(path.string() + ": reading the GIF back failed: " + std::strerror(errno));
  }
  const std::string tagged = withGifComment(gif, comment);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(tagged.data(), static_cast<std::streamsize>(tagged.size()));
  out.close();
  if (!out) throw std::runtime_error(path.string() + ": writing the GIF's comment failed: " + std::strerror(errno));
}

}  // namespace coinroll::video
