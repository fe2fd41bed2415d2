#include "io/runtime_library.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <mutex>
#include <stdexcept>
#include <utility>

namespace coinroll::io {

RuntimeLibrary::RuntimeLibrary(std::string soname, std::string package)
    : soname_(std::move(soname)), package_(std::move(package)) {}

void* RuntimeLibrary::symbol(const char* name) {
  // Render threads (the async sink's encoder, the frame loop) may reach a library first at once.
  static std::mutex opening;
  {
    const std::lock_guard lock(opening);
    if (handle_ == nullptr) {
      handle_ = dlopen(soname_.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (handle_ == nullptr) {
        const char* reason = dlerror();
        throw std::runtime_error(fmt::format("cannot load {} ({}), which rendering needs: install {} (tools/setup.sh)",
                                             soname_, reason ? reason : "no reason given", package_));
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
