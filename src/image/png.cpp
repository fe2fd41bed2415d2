#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <array>
#include <initializer_list>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "image/image.h"
#include "io/output_file.h"

#include <stb_image.h>
#include <stb_image_write.h>
#include <zlib.h>

namespace coinroll::image {

namespace {

// stb's zlib output depends only on the pixels and this level, so equal pixels give equal bytes.
constexpr int kPngCompressionLevel = 8;

void appendBigEndian32(std::vector<unsigned char>& bytes, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) bytes.push_back(static_cast<unsigned char>(value >> shift));
}

// stb writes no text; the chunks go right after IHDR (the 8-byte signature, then IHDR's 4-byte
// length, type, 13 data bytes and CRC), where readers that stop early still find them.
void insertTextChunks(std::vector<unsigned char>& png, const PngText& text) {
  constexpr std::size_t kAfterHeader = 8 + 4 + 4 + 13 + 4;
  std::vector<unsigned char> chunks;
  for (const auto& [key, value] : text) {
    if (key.empty() || key.size() > 79 || key.find('\0') != std::string::npos ||
        value.find('\0') != std::string::npos) {
      throw std::invalid_argument("PNG text key '" + key +
                                  "': must be 1 to 79 characters with no NUL, as must its text");
    }
    const std::size_t start = chunks.size();
    appendBigEndian32(chunks, static_cast<std::uint32_t>(key.size() + 1 + value.size()));
    for (const char c : std::string("tEXt") + key + '\0' + value) chunks.push_back(static_cast<unsigned char>(c));
    const uLong crc =
        crc32(crc32(0L, Z_NULL, 0), chunks.data() + start + 4, static_cast<uInt>(chunks.size() - start - 4));
    appendBigEndian32(chunks, static_cast<std::uint32_t>(crc));
  }
  png.insert(png.begin() + kAfterHeader, chunks.begin(), chunks.end());
}

// The PNG file's bytes. Encoded in memory and written by the caller: stbi_write_png's own file
// output ignores fwrite's and fclose's results, so a full disk would pass as success.
std::vector<unsigned char> encodePng(const Image& image, const std::filesystem::path& name, const PngText& text) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
    throw std::runtime_error(name.string() + ": refusing to write an empty or inconsistent image");
  }
  stbi_write_png_compression_level = kPngCompressionLevel;
  std::vector<unsigned char> png;
  const auto append = [](void* context, void* data, int size) {
    auto* bytes = static_cast<unsigned char*>(data);
    static_cast<std::vector<unsigned char>*>(context)->insert(static_cast<std::vector<unsigned char>*>(context)->end(),
                                                              bytes, bytes + size);
  };
  // Sizes and data were checked above, so stb fails only to allocate its buffers.
  if (stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4) == 0) {
    throw std::bad_alloc();
  }
  insertTextChunks(png, text);
  return png;
}

// stb reports a failed allocation as "outofmem"; it is not a fault of the file.
// Some of its failures (compressed data that does not inflate) leave no reason at all.
[[noreturn]] void throwDecodeFailure(const std::string& context) {
  const char* failure = stbi_failure_reason();
  const std::string reason = failure != nullptr ? failure : "its compressed pixel data does not inflate";
  if (reason == "outofmem") throw std::bad_alloc();
  throw std::runtime_error(context + reason);
}

}  // namespace

void writePngBytes(const Image& image, const std::filesystem::path& path, const std::filesystem::path& name,
                   const PngText& text) {
  const std::vector<unsigned char> png = encodePng(image, name, text);
  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (out == nullptr) throw std::runtime_error(name.string() + ": cannot open for writing: " + std::strerror(errno));
  const bool written = std::fwrite(png.data(), 1, png.size(), out) == png.size() && std::fflush(out) == 0;
  const int writeError = errno;
  const bool closed = std::fclose(out) == 0;
  if (!written || !closed) {
    throw std::runtime_error(name.string() +
                             ": writing the PNG failed: " + io::describeWriteError(written ? errno : writeError));
  }
}

// Through the output layer: atomic for a file (a link's target included), streamed to a device,
// FIFO or descriptor (io/output_file.h).
void writePng(const Image& image, const std::filesystem::path& path, const PngText& text) {
  io::OutputFile file(path, "PNG");
  const std::vector<unsigned char> png = encodePng(image, path, text);
  file.write(std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
  file.commit();
}

// Read by hand: stb's own header reader refuses pictures above 1 GiB without saying their size.
PngSize readPngSize(const std::filesystem::path& path) {
  // The signature, then the IHDR chunk, which PNG requires first: length 13, "IHDR", width and
  // height as big-endian 32-bit numbers.
  constexpr unsigned char kStart[16] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
  unsigned char head[26] = {};
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (in == nullptr) throw std::runtime_error(path.string() + ": cannot open: " + std::strerror(errno));
  const std::size_t got = std::fread(head, 1, sizeof head, in);
  std::fclose(in);
  if (got != sizeof head || std::memcmp(head, kStart, sizeof kStart) != 0) {
    throw std::runtime_error(path.string() + ": cannot read the PNG header: no IHDR chunk where PNG puts it");
  }
  const auto number = [&](int at) {
    return static_cast<std::uint32_t>(head[at]) << 24 | static_cast<std::uint32_t>(head[at + 1]) << 16 |
           static_cast<std::uint32_t>(head[at + 2]) << 8 | static_cast<std::uint32_t>(head[at + 3]);
  };
  // PNG allows sides up to 2^31 - 1, and 0 nowhere.
  const std::uint32_t width = number(16), height = number(20);
  if (width == 0 || height == 0 || width > 0x7fffffffu || height > 0x7fffffffu) {
    throw std::runtime_error(path.string() + ": cannot read the PNG header: a side of " +
                             std::to_string(width == 0 || width > 0x7fffffffu ? width : height) + " pixels");
  }
  // PNG's table of depths per colour type: stb takes some other pairs for another fault ("invalid
  // width" for a 4-bit RGB picture), so they are named here.
  const int depth = head[24], colourType = head[25];
  const auto depthAllowed = [&](std::initializer_list<int> depths) {
    return std::find(depths.begin(), depths.end(), depth) != depths.end();
  };
  const bool allowed = colourType == 0                                         ? depthAllowed({1, 2, 4, 8, 16})
                       : colourType == 3                                       ? depthAllowed({1, 2, 4, 8})
                       : colourType == 2 || colourType == 4 || colourType == 6 ? depthAllowed({8, 16})
                                                                               : false;
  if (!allowed) {
    throw std::runtime_error(path.string() + ": cannot read the PNG header: bit depth " + std::to_string(depth) +
                             " with colour type " + std::to_string(colourType) + " is not allowed in PNG");
  }
  return {static_cast<int>(width), static_cast<int>(height), depth};
}

void checkPngChunks(const std::filesystem::path& path) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!in) throw std::runtime_error(path.string() + ": cannot open: " + std::strerror(errno));
  const auto fail = [&](long offset, const std::string& what) {
    throw std::runtime_error(path.string() + ": " + what + " at byte " + std::to_string(offset) +
                             ": a damaged or truncated PNG");
  };
  const auto bigEndian = [](const unsigned char* b) {
    return static_cast<std::uint32_t>(b[0]) << 24 | static_cast<std::uint32_t>(b[1]) << 16 |
           static_cast<std::uint32_t>(b[2]) << 8 | static_cast<std::uint32_t>(b[3]);
  };
  long offset = 8;  // past the signature, which readPngSize checks
  if (std::fseek(in.get(), offset, SEEK_SET) != 0) fail(0, "no PNG signature");
  std::array<unsigned char, 1 << 16> block{};
  while (true) {
    unsigned char head[8];
    if (std::fread(head, 1, sizeof head, in.get()) != sizeof head) fail(offset, "the file ends before its IEND chunk");
    const std::uint32_t length = bigEndian(head);
    const std::string type(reinterpret_cast<const char*>(head + 4), 4);
    if (length > 0x7fffffffu) fail(offset, "chunk " + type + " declares " + std::to_string(length) + " bytes");
    uLong crc = crc32(0, head + 4, 4);
    for (std::uint32_t left = length; left > 0;) {
      const std::size_t want = std::min<std::size_t>(left, block.size());
      if (std::fread(block.data(), 1, want, in.get()) != want) fail(offset, "chunk " + type + " is cut short");
      crc = crc32(crc, block.data(), static_cast<uInt>(want));
      left -= static_cast<std::uint32_t>(want);
    }
    unsigned char stored[4];
    if (std::fread(stored, 1, sizeof stored, in.get()) != sizeof stored) fail(offset, "chunk " + type + " has no CRC");
    if (bigEndian(stored) != static_cast<std::uint32_t>(crc)) fail(offset, "chunk " + type + " fails its CRC check");
    if (type == "IEND") return;
    offset += 12 + static_cast<long>(length);
  }
}

Image readPng(const std::filesystem::path& path) {
  int width = 0, height = 0, channels = 0;
  // Opened here, not by stb, whose message for an unopenable file is "can't fopen", without errno's.
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!in) throw std::runtime_error(path.string() + ": cannot read PNG: " + std::strerror(errno));
  stbi_uc* data = stbi_load_from_file(in.get(), &width, &height, &channels, 4);
  if (data == nullptr) throwDecodeFailure(path.string() + ": cannot read PNG: ");
  Image image(width, height);
  std::copy(data, data + image.rgba.size(), image.rgba.begin());
  stbi_image_free(data);
  return image;
}

Image decodePng(std::span<const std::uint8_t> bytes, std::string_view name) {
  int width = 0, height = 0, channels = 0;
  stbi_uc* data = stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width, &height, &channels, 4);
  if (data == nullptr) throwDecodeFailure(std::string(name) + ": cannot decode PNG: ");
  Image image(width, height);
  std::copy(data, data + image.rgba.size(), image.rgba.begin());
  stbi_image_free(data);
  return image;
}

}  // namespace coinroll::image
