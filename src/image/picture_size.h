#pragma once
// The picture size a run gets when nothing names one (720p). Here, below both render and video,
// so the renderer's default picture and the encoder's default frame cannot drift apart.

namespace coinroll::image {

inline constexpr int kDefaultPictureWidth = 1280;  // pixels
inline constexpr int kDefaultPictureHeight = 720;  // pixels

}  // namespace coinroll::image
