#pragma once
// Test support: the one golden rule of every image test. Exact bytes by default; on a CPU other
// than the goldens' (llvmpipe rounds a few edge pixels per CPU), COINROLL_GOLDEN_TOLERANT=1.

namespace coinroll::testing {

// Whether COINROLL_GOLDEN_TOLERANT=1 asks for image::otherCpuThresholds() instead of exact bytes
// (docs/snapshot_testing.md). Throws std::invalid_argument for any value but 1, 0 or unset, so a
// typo never silently means exact or tolerant.
bool goldenTolerant();

}  // namespace coinroll::testing
