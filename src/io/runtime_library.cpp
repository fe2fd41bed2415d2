#include "io/runtime_library.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <mutex>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace coinroll::io {

RuntimeLibrary::RuntimeLibrary(std::string soname, std::string package)
    : soname_(std::move(soname)), package_(std::move(package)) {}

std::string RuntimeLibrary::loadFailure(std::string_view reason) const {
  // The loader names the file that failed first ("libavcodec.so.59: invalid ELF header"): where
  // that is a library ours needs, installing our package again is not the fix.
  const std::string_view failed = reason.substr(0, reason.find(": "));
  const std::string_view failedName = failed.substr(failed.rfind('/') + 1);
  const std::string_view ownName = std::string_view(soname_).substr(soname_.rfind('/') + 1);
  if (failed.size() < reason.size() && failedName.find(".so") != std::string_view::npos && failedName != ownName) {
    return fmt::format(
        "cannot load {}: a library it needs, {}, cannot be loaded ({}); rendering needs both: reinstall "
        "the package that provides {} (`dpkg -S {}` names it), or {} (tools/setup.sh)",
        soname_, failedName, reason, failedName, failedName, package_);
  }
  return fmt::format("cannot load {} ({}), which rendering needs: install {} (tools/setup.sh)", soname_, reason,
                     package_);
}

void* RuntimeLibrary::symbol(const char* name) {
  // Render threads (the async sink's encoder, the frame loop) may reach a library first at once.
  static std::mutex opening;
  {
    const std::lock_guard lock(opening);
    if (handle_ == nullptr) {
      handle_ = dlopen(soname_.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (handle_ == nullptr) {
        const char* reason = dlerror();
        throw std::runtime_error(loadFailure(reason ? reason : "no reason given"));
      }
    }
  }
  dlerror();
  void* address = dlsym(handle_, name);
  if (address == nullptr) {
    throw std::runtime_error(fmt::format("{} has no function {}: coinroll was built against another version of {}",
                                         soname_, name, package_));
  }
  return address;
}

}  // namespace coinroll::io
