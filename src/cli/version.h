#pragma once
// What `coinroll --version` prints (docs/contract.md §8).

#include <string>

namespace coinroll::cli {

// `git describe --always --dirty` of the checkout the binary was built from, read at build time
// (cmake/git_revision.cmake); empty for a build outside a checkout.
extern const char* const kGitRevision;

// "coinroll 0.1.0 (git 83f6561a2b3c)" and, on a second line, the OpenGL back ends compiled in and
// the one COINROLL_GL selects (or why its value selects none). Opens no GL context.
std::string versionText();

}  // namespace coinroll::cli
