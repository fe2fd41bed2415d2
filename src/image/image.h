#pragma once
// An 8-bit RGBA picture, rows stored top to bottom (the renderer flips OpenGL's bottom-up
// readback once, so every consumer sees the usual image orientation).

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace coinroll::image {

struct Image {
  int width = 0;                   // pixels
  int height = 0;                  // pixels
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes, row 0 is the top

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0) {}

  std::uint8_t* pixel(int x, int y) { return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4; }
  const std::uint8_t* pixel(int x, int y) const { return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4; }
};

// Key and text pairs a PNG carries as tEXt chunks, in order, right after its header (keys of 1 to
// 79 Latin-1 characters, no NUL in either; std::invalid_argument otherwise).
using PngText = std::vector<std::pair<std::string, std::string>>;

// Writes `image` as PNG to `path` atomically (temporary file, then rename). Throws
// std::runtime_error naming the path on failure; nothing is left under `path` then.
void writePng(const Image& image, const std::filesystem::path& path, const PngText& text = {});

// Encodes `image` and writes the bytes to `path` itself, checking every write and the close
// (std::runtime_error naming `name`, the output the user asked for, with the system's reason on a
// full disk or any other failure); making the result appear atomically is the caller's business.
void writePngBytes(const Image& image, const std::filesystem::path& path, const std::filesystem::path& name,
                   const PngText& text = {});

// The size a PNG's header declares, pixels, and its bits per channel (1, 2, 4, 8 or 16).
struct PngSize {
  int width = 0;
  int height = 0;
  int bitDepth = 8;
};

// Reads the header of the PNG at `path` only, so a caller can judge the size before decoding it
// (a small file may declare a picture of gigabytes). Throws std::runtime_error naming the path
// when it is not a PNG.
PngSize readPngSize(const std::filesystem::path& path);

// Walks every chunk of the PNG at `path` and checks its CRC, up to the IEND chunk that ends a
// PNG; the decoder ignores CRCs, so a damaged file would otherwise decode as if whole. Throws
// std::runtime_error naming the path, the chunk and its byte offset.
void checkPngChunks(const std::filesystem::path& path);

// Reads an 8-bit PNG as RGBA. Throws std::runtime_error naming the path on failure, and
// std::bad_alloc when the decoded picture does not fit in memory.
Image readPng(const std::filesystem::path& path);

// Decodes PNG bytes held in memory (e.g. an asset embedded in the binary) as RGBA. Throws
// std::runtime_error naming `name` on failure.
Image decodePng(std::span<const std::uint8_t> bytes, std::string_view name);

}  // namespace coinroll::image
