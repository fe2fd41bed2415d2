#include <stdexcept>
#include <string>

#include "image/image.h"
#include "io/atomic_file.h"

#include <stb_image.h>
#include <stb_image_write.h>

namespace coinroll::image {

void writePng(const Image& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
    throw std::runtime_error(path.string() + ": refusing to write an empty or inconsistent image");
  }
  io::AtomicOutputFile file(path);
  // stb's zlib output depends only on the pixels and this level, so equal pixels give equal bytes.
  stbi_write_png_compression_level = 8;
  if (stbi_write_png(file.temporaryPath().c_str(), image.width, image.height, 4, image.rgba.data(),
                     image.width * 4) == 0) {
    throw std::runtime_error(path.string() + ": PNG encoding or writing failed");
  }
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
