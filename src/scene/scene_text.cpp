#include "scene/scene_text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "scene/json_reader.h"
#include "scene/scene_error.h"

namespace coinroll::scene {

namespace {

// 1-based line and column of a byte offset in `text`.
std::pair<std::size_t, std::size_t> lineAndColumn(std::string_view text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < std::min(byte, text.size()); ++i) {
    if (text[i] == '\n')
      ++line, column = 1;
    else
      ++column;
  }
  return {line, column};
}

// nlohmann's parse error without its own position prefix (we give line and column) and with the
// bytes it quotes from the input made printable: the input may be anything, even not UTF-8.
std::string parseErrorReason(const nlohmann::json::parse_error& error) {
  std::string_view what = error.what();
  if (const auto column = what.find(", column "); column != std::string_view::npos) {
    if (const auto colon = what.find(": ", column); colon != std::string_view::npos) what.remove_prefix(colon + 2);
  }
  std::string reason;
  for (const char c : what) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte >= 0x7f)
      reason += fmt::format("\\x{:02x}", byte);
    else
      reason += c;
  }
  return reason;
}

// A key given twice in one object: nlohmann keeps the last value silently, so a scene that says
// theta twice would run with whichever came last. Thrown from the parser's callback.
struct DuplicateKey {
  std::string path;  // "initial.theta", "effects.0.length"
};

// An array or object wider than a scene can mean, at `path`. Thrown from the parser's callback.
struct TooWide {
  std::string path;
};

// A scene's arrays and objects hold a handful of values. One of millions (a 16 MB array of zeros is
// eight million) takes 16 bytes a value to hold and as much again to free, as nlohmann's destructor
// first moves the elements onto a list of its own: near the address-space limit that second
// allocation, made while the scene's error unwound, ended the program in std::terminate.
constexpr std::size_t kMaxSceneWidth = 1 << 16;

// The parser's callback, refusing duplicate keys and arrays or objects wider than kMaxSceneWidth. It
// follows the nesting: each open object keeps the keys seen so far, each open array its element
// count, so a duplicate or a wide value is named by its path.
class DuplicateKeyGuard {
 public:
  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        frames_.push_back({.name = nameOfNextValue(),
                           .isArray = event == Event::array_start,
                           .elements = 0,
                           .keys = {},
                           .pendingKey = {}});
        break;
      case Event::object_end:
      case Event::array_end: frames_.pop_back(); break;
      case Event::key: {
        std::string key = parsed.get<std::string>();
        if (!frames_.back().keys.insert(key).second) throw DuplicateKey{joinedPath(key)};
        if (frames_.back().keys.size() > kMaxSceneWidth) throw TooWide{pathOfInnermost()};
        frames_.back().pendingKey = std::move(key);
        break;
      }
      case Event::value: nameOfNextValue(); break;
    }
    return true;
  }

 private:
  struct Frame {
    std::string name;  // the key or index this object or array has in its parent
    bool isArray = false;
    long elements = 0;
    std::set<std::string> keys;
    std::string pendingKey;
  };

  // The name of the value that starts now in the innermost open object or array.
  std::string nameOfNextValue() {
    if (frames_.empty()) return {};
    Frame& parent = frames_.back();
    if (!parent.isArray) return parent.pendingKey;
    if (static_cast<std::size_t>(parent.elements) >= kMaxSceneWidth) throw TooWide{pathOfInnermost()};
    return std::to_string(parent.elements++);
  }

  std::string joinedPath(const std::string& key) const {
    std::string path;
    for (std::size_t i = 1; i < frames_.size(); ++i) path += printableKey(frames_[i].name) + ".";
    return path + printableKey(key);
  }

  // The innermost open array's or object's path, "(top level)" for the document itself.
  std::string pathOfInnermost() const {
    if (frames_.size() < 2) return "(top level)";
    std::string path = printableKey(frames_[1].name);
    for (std::size_t i = 2; i < frames_.size(); ++i) {
      path += '.';
      path += printableKey(frames_[i].name);
    }
    return path;
  }

  std::vector<Frame> frames_;
};

}  // namespace

nlohmann::json readSceneDocument(const std::filesystem::path& file) {
  if (file.empty()) {
    throw SceneError(
        "the scene file name is empty; give a scene file (e.g. examples/steady_circle.json), or none for "
        "the built-in scene");
  }
  std::error_code error;
  if (std::filesystem::is_directory(file, error)) {
    throw SceneError(fmt::format("{}: is a directory; give a scene file (JSON)", file.string()));
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(fmt::format("{}: cannot open the scene file: {}", file.string(), std::strerror(errno)));
  return readSceneDocument(in, file.string());
}

nlohmann::json readSceneDocument(std::istream& in, std::string_view sourceName) {
  // Scenes are a few hundred bytes. The read stops past this, so a huge file given by mistake, or
  // a device that never ends (/dev/zero), is refused instead of filling memory; pipes still work.
  // Read in chunks, so a scene of a few hundred bytes takes a few kilobytes, not the limit.
  constexpr std::size_t kMaxSceneBytes = 16 << 20;
  constexpr std::size_t kChunkBytes = 64 << 10;
  std::string text;
  while (in && text.size() <= kMaxSceneBytes) {
    const std::size_t before = text.size();
    text.resize(before + std::min(kChunkBytes, kMaxSceneBytes + 1 - before));
    in.read(text.data() + before, static_cast<std::streamsize>(text.size() - before));
    text.resize(before + static_cast<std::size_t>(in.gcount()));
  }
  if (text.size() > kMaxSceneBytes) {
    throw SceneError(
        fmt::format("{}: more than {} bytes; a scene file is a small JSON document", sourceName, kMaxSceneBytes));
  }
  return parseSceneText(text, sourceName);
}

nlohmann::json parseSceneText(std::string_view text, std::string_view sourceName) {
  // nlohmann's lexer takes a NUL byte for the end of the input, so whatever follows one would go
  // unread: a damaged file, or a binary one, would pass as the scene before it.
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
    const auto [line, column] = lineAndColumn(text, nul);
    throw SceneError(
        fmt::format("{}: invalid JSON at line {}, column {}: a NUL byte; a scene file is JSON text "
                    "(a damaged or binary file?)",
                    sourceName, line, column));
  }
  try {
    return nlohmann::json::parse(text, DuplicateKeyGuard());
  } catch (const TooWide& wide) {
    throw SceneError(fmt::format("{}: {}: more than {} values in one array or object; {}", sourceName, wide.path,
                                 kMaxSceneWidth, "a scene file is a small JSON document"));
  } catch (const DuplicateKey& duplicate) {
    throw SceneError(
        fmt::format("{}: {}: given twice; give each key once (which value was meant?)", sourceName, duplicate.path));
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports the byte just past the offending token; its own text says what was expected.
    const auto [line, column] = lineAndColumn(text, e.byte == 0 ? 0 : e.byte - 1);
    throw SceneError(
        fmt::format("{}: invalid JSON at line {}, column {}: {}", sourceName, line, column, parseErrorReason(e)));
  } catch (const nlohmann::json::exception& e) {
    // E.g. a number beyond double range ("1e400"): not finite, so never a valid value.
    std::string reason = e.what();
    if (const auto bracket = reason.find("] "); bracket != std::string::npos) reason = reason.substr(bracket + 2);
    throw SceneError(fmt::format("{}: invalid JSON: {} (numbers must be finite doubles)", sourceName, reason));
  }
}

}  // namespace coinroll::scene
