#pragma once
// A shared library the program opens when it first calls into it, not at start-up. Rendering's
// libraries (FFmpeg, OSMesa, EGL) pull in about 140 others, Mesa's LLVM among them: linked, they
// cost every command, `simulate` and `--version` too, some 50 ms of loading before main. Their
// functions are defined in src/video and src/render as forwarders of the same names and types
// (COINROLL_FORWARD), so the code that calls them is unchanged.

#include <string>
#include <string_view>

namespace coinroll::io {

class RuntimeLibrary {
 public:
  // soname: "libavcodec.so.59", fixed when coinroll was built (the headers it was compiled
  // against); package: what provides it, for the message when it cannot be opened.
  RuntimeLibrary(std::string soname, std::string package);
  RuntimeLibrary(const RuntimeLibrary&) = delete;
  RuntimeLibrary& operator=(const RuntimeLibrary&) = delete;

  // The address of `name`, the library opened on first use. Throws std::runtime_error naming the
  // library, its package and the loader's reason when either cannot be found; where the loader
  // failed on a library ours needs, naming that one as what to repair.
  void* symbol(const char* name);

 private:
  std::string loadFailure(std::string_view reason) const;

  std::string soname_, package_;
  void* handle_ = nullptr;
};

}  // namespace coinroll::io

// Defines the C function `name`, declared by the library's own header (so a parameter list that
// differs from it fails to compile), as a call through its address in `library`, looked up once.
#define COINROLL_FORWARD(library, result, name, parameters, arguments)                       \
  extern "C" result name parameters {                                                        \
    static const auto function = reinterpret_cast<decltype(&name)>((library).symbol(#name)); \
    return function arguments;                                                               \
  }
