#pragma once

#include <stdexcept>
#include <string>

namespace coinroll::scene {

class SceneError : public std::runtime_error {
 public:
  // UnknownKey: the document or a --set path names a field the scene format does not have (a
  // typo, usually), as opposed to a field whose value is wrong; sweeps refuse it before any work.
  // WrongType: the field holds another kind of JSON value (an object, a string, a list...) than given.
  enum class Kind { BadValue, UnknownKey, WrongType };
  explicit SceneError(const std::string& message, Kind kind = Kind::BadValue)
      : std::runtime_error(message), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

}  // namespace coinroll::scene
