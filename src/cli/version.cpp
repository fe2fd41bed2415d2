#include "cli/version.h"

#include <fmt/format.h>

#include "render/gl_backend.h"

namespace coinroll::cli {

std::string versionText() {
  const std::string revision = *kGitRevision != '\0' ? fmt::format(" (git {})", kGitRevision) : "";
  return fmt::format("coinroll {}{}\n{}", COINROLL_VERSION, revision, render::glBackendsLine());
}

}  // namespace coinroll::cli
