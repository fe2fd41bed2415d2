#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>
#include <stdexcept>
#include <string>

#include "image/image.h"
#include "io/atomic_file.h"

#include <stb_image.h>
#include <stb_image_write.h>

namespace coinroll::image {

void writePngBytes(const Image& image, const std::filesystem::path& path, const std::filesystem::path& name) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
    throw std::runtime_error(name.string() + ": refusing to write an empty or inconsistent image");
  }
  // stb's zlib output depends only on the pixels and this level, so equal pixels give equal bytes.
  stbi_write_png_compression_level = 8;
  // Encoded in memory and written here: stbi_write_png's own file output ignores fwrite's and
  // fclose's results, so a full disk would pass as success with a truncated file.
  std::vector<unsigned char> png;
  const auto append = [](void* context, void* data, int size) {
    auto* bytes = static_cast<unsigned char*>(data);
    static_cast<std::vector<unsigned char>*>(context)->insert(static_cast<std::vector<unsigned char>*>(context)->end(),
                                                              bytes, bytes + size);
  };
  if (stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4) == 0) {
    throw std::runtime_error(name.string() + ": PNG encoding failed");
  }
  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (out == nullptr) throw std::runtime_error(name.string() + ": cannot open for writing: " + std::strerror(errno));
  const bool written = std::fwrite(png.data(), 1, png.size(), out) == png.size() && std::fflush(out) == 0;
  const int writeError = errno;
  const bool closed = std::fclose(out) == 0;
  if (!written || !closed) {
    throw std::runtime_error(name.string() + ": writing the PNG failed: " + std::strerror(written ? errno : writeError));
  }
}

void writePng(const Image& image, const std::filesystem::path& path) {
  io::AtomicOutputFile file(path);
  writePngBytes(image, file.temporaryPath(), path);
  file.commit();
}

Image readPng(const std::filesystem::path& path) {
  int width = 0, height = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &width, &height, &channels, 4);
  if (data == nullptr) {
    throw std::runtime_error(path.string() + ": cannot read PNG: " + stbi_failure_reason());
  }
  Image image(width, height);
  std::copy(data, data + image.rgba.size(), image.rgba.begin());
  stbi_image_free(data);
  return image;
}

Image decodePng(std::span<const std::uint8_t> bytes, std::string_view name) {
  int width = 0, height = 0, channels = 0;
  stbi_uc* data = stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width, &height, &channels, 4);
  if (data == nullptr) throw std::runtime_error(std::string(name) + ": cannot decode PNG: " + stbi_failure_reason());
  Image image(width, height);
  std::copy(data, data + image.rgba.size(), image.rgba.begin());
  stbi_image_free(data);
  return image;
}

}  // namespace coinroll::image
