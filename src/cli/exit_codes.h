#pragma once

#include <stdexcept>

namespace coinroll::cli {

// docs/contract.md: 0 success; 2 bad command line or bad scene (nothing written); 1 any other failure.
inline constexpr int kExitSuccess = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

// Bad command-line values found after parsing (CLI11 reports its own with the same exit code).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace coinroll::cli
