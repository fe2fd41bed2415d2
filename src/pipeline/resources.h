#pragma once
// Memory as the process may use it: the address-space limit (`ulimit -v`, RLIMIT_AS), checks
// made before work that a library would otherwise start and then crash or hang in when memory
// runs out (OpenGL under llvmpipe does not check its allocations), and messages that name what
// ran out. Without a limit nothing is refused here: the machine's memory cannot be predicted.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "render/render_settings.h"

namespace coinroll::pipeline {

// Bytes of address space the process may map (RLIMIT_AS), or nullopt when unlimited.
std::optional<std::uint64_t> addressSpaceLimit();

// Bytes of address space the process maps now (its VmSize).
std::uint64_t addressSpaceInUse();

// What memory there is to run out of, for messages: "the address-space limit of 440 MiB
// (ulimit -v 450000)", or "the machine's memory" without a limit.
std::string memoryLimitDescription();

// The message for an allocation that failed (std::bad_alloc): "out of memory: <the limit> is used
// up; ...", with what to do.
std::string outOfMemoryMessage();

// Under an address-space limit, throws std::runtime_error naming `what`, the bytes it needs, the
// bytes left and `remedy` when fewer than `bytes` are left unmapped; nothing without a limit.
void requireAddressSpace(std::uint64_t bytes, std::string_view what, std::string_view remedy);

// Bytes of address space a render::Renderer with `settings` maps beyond what the process mapped
// before it: the OpenGL context (llvmpipe's threads and compiled shaders) and the framebuffers.
// An upper estimate from measurements (resources.cpp), so that a limit it passes lets the
// renderer start and draw.
std::uint64_t rendererAddressSpace(const render::RenderSettings& settings);

// requireAddressSpace(rendererAddressSpace(settings) + encoderBytes, ...) naming the pictures and
// what to ask for instead; for callers about to construct a render::Renderer. `encoderBytes`:
// what the frames' sink will allocate (video::FrameSink::workingMemory).
void requireRendererAddressSpace(const render::RenderSettings& settings, std::uint64_t encoderBytes = 0);

// Under an address-space limit, makes malloc serve every thread from one arena: glibc otherwise
// reserves 64 MiB of address space for each thread's arena, which under a limit of a few hundred
// MiB made whether OpenGL started depend on the limit's value modulo those reservations, not on
// how much was left (measured: failures at every size from 360 to 780 MB, successes between).
// For the program to call once, before it starts threads; nothing without a limit.
void fitAllocatorToAddressSpaceLimit();

}  // namespace coinroll::pipeline
