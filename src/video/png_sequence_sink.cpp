#include "video/png_sequence_sink.h"

#include <cctype>
#include <climits>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "video/video_kinds.h"

namespace coinroll::video {

namespace {

constexpr int kMaxDigits = 10;  // an int has at most 10 decimal digits

std::invalid_argument badPattern(const std::string& pattern, const std::string& rule) {
  return std::invalid_argument(pattern + ": bad PNG sequence pattern: " + rule +
                               " (expected one %d or %0Nd conversion and a .png ending, e.g. frame_%05d.png)");
}

}  // namespace

bool looksLikeSequencePattern(const std::string& fileName) {
  for (std::size_t i = 0; i < fileName.size(); ++i) {
    if (fileName[i] != '%') continue;
    if (i + 1 < fileName.size() && fileName[i + 1] == '%') {
      ++i;
      continue;
    }
    return true;
  }
  return false;
}

SequencePattern parseSequencePattern(const std::filesystem::path& pattern) {
  const std::string whole = pattern.string();
  const std::string fileName = pattern.filename().string();
  SequencePattern parsed;
  bool haveConversion = false;
  std::string* literal = &parsed.prefix;
  for (std::size_t i = 0; i < fileName.size(); ++i) {
    if (fileName[i] != '%') {
      literal->push_back(fileName[i]);
      continue;
    }
    if (i + 1 < fileName.size() && fileName[i + 1] == '%') {
      literal->push_back('%');
      ++i;
      continue;
    }
    if (haveConversion) throw badPattern(whole, "more than one % conversion");
    // Parse [0[digits]]d; width without the zero flag would pad with spaces, which we refuse.
    std::size_t j = i + 1;
    if (j < fileName.size() && fileName[j] == '0') {
      ++j;
      std::size_t widthStart = j;
      while (j < fileName.size() && std::isdigit(static_cast<unsigned char>(fileName[j]))) ++j;
      if (j == widthStart || j - widthStart > 2) throw badPattern(whole, "the zero flag needs a width of 1..10");
      parsed.minimumDigits = std::stoi(fileName.substr(widthStart, j - widthStart));
      if (parsed.minimumDigits < 1 || parsed.minimumDigits > kMaxDigits) {
        throw badPattern(whole, "the zero flag needs a width of 1..10");
      }
    }
    if (j >= fileName.size() || fileName[j] != 'd') throw badPattern(whole, "only %d and %0Nd are supported");
    haveConversion = true;
    literal = &parsed.suffix;
    i = j;
  }
  if (!haveConversion) throw badPattern(whole, "no % conversion");
  if (!namesExtension(fileName, kPngExtension)) throw badPattern(whole, "the file name must end in .png");
  return parsed;
}

std::string SequencePattern::fileNameOf(int index) const {
  std::string number = std::to_string(index);
  if (static_cast<int>(number.size()) < minimumDigits) number.insert(0, minimumDigits - number.size(), '0');
  return prefix + number + suffix;
}

std::optional<int> SequencePattern::frameNumberOf(std::string_view fileName) const {
  if (fileName.size() <= prefix.size() + suffix.size() || !fileName.starts_with(prefix) ||
      !fileName.ends_with(suffix)) {
    return std::nullopt;
  }
  const std::string_view digits = fileName.substr(prefix.size(), fileName.size() - prefix.size() - suffix.size());
  if (digits.size() > static_cast<std::size_t>(kMaxDigits) ||
      digits.find_first_not_of("0123456789") != std::string_view::npos) {
    return std::nullopt;
  }
  const long long number = std::stoll(std::string(digits));
  // Only the exact name the pattern gives that number: "f_0004.png" is no frame of f_%03d.png.
  if (number > INT_MAX || fileNameOf(static_cast<int>(number)) != fileName) return std::nullopt;
  return static_cast<int>(number);
}

PngSequenceSink::PngSequenceSink(std::filesystem::path pattern, const std::vector<std::filesystem::path>& inputs,
                                 const Provenance& provenance, io::OutputGroup* group)
    : pattern_(parseSequencePattern(pattern)), text_(provenance.pngText()), frames_(group ? *group : ownFrames_) {
  frames_.protect(inputs);
  const std::string whole = pattern.string();
  directory_ = pattern.parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(directory_.empty() ? "." : directory_, ec)) {
    throw std::runtime_error(whole + ": cannot write: directory '" + directory_.string() + "' does not exist");
  }
  // Only a name that exists can lead to an input: refused here, before any frame is rendered, as
  // an output named like an input is (exit 2). add() checks again when the frame is written.
  for (const std::filesystem::path& frame : framesFrom(0)) {
    if (const std::optional<std::filesystem::path> input = frames_.inputBehind(frame)) {
      throw std::invalid_argument(frame.string() + ": cannot write: it leads to " + input->string() +
                                  ", an input of this command (through a link, or as another name of that file); "
                                  "choose another output name");
    }
  }
}

PngSequenceSink::~PngSequenceSink() = default;  // an uncommitted group removes its temporaries

std::filesystem::path PngSequenceSink::pathOfFrame(int index) const { return directory_ / pattern_.fileNameOf(index); }

void PngSequenceSink::push(const image::Image& frame) {
  if (finished_) throw std::logic_error(pathOfFrame(0).string() + ": push() after finish()");
  const std::filesystem::path name = pathOfFrame(frameCount_);
  image::writePngBytes(frame, frames_.add(name, "PNG"), name, text_);
  ++frameCount_;
}

std::vector<std::filesystem::path> PngSequenceSink::framesFrom(int count) const {
  std::vector<std::filesystem::path> frames;
  std::error_code error;
  const std::filesystem::path directory = directory_.empty() ? "." : directory_;
  for (std::filesystem::directory_iterator entry(directory, error), end; !error && entry != end;
       entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    const std::optional<int> number = pattern_.frameNumberOf(name);
    if (!number || *number < count) continue;
    // A directory or a device named like a frame was never one of ours: it stays where it is.
    const std::filesystem::file_type type = entry->symlink_status(error).type();
    if (error) break;
    if (type != std::filesystem::file_type::regular && type != std::filesystem::file_type::symlink) continue;
    frames.push_back(directory_ / name);
  }
  if (error) {
    throw std::runtime_error(pathOfFrame(0).string() + ": cannot list '" + directory.string() +
                             "' for frames of an earlier sequence: " + error.message());
  }
  return frames;
}

void PngSequenceSink::finish() {
  if (finished_) throw std::logic_error(pathOfFrame(0).string() + ": finish() called twice");
  if (frameCount_ == 0) throw std::runtime_error(pathOfFrame(0).string() + ": no frames to write");
  for (const std::filesystem::path& stale : framesFrom(frameCount_)) frames_.retire(stale, "PNG");
  if (&frames_ == &ownFrames_) frames_.commit();
  finished_ = true;
}

}  // namespace coinroll::video
