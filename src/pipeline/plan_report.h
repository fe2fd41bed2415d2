#pragma once
// What a clip's plan says in words: `render --plan`'s report, and the line the overlay adds about
// the pace a frame plays at.

#include <string>
#include <vector>

#include "pipeline/clip_window.h"
#include "pipeline/playback_clock.h"

namespace coinroll::pipeline {

// `render --plan`'s report: the video's length and frames, the simulated span, the frames `window`
// keeps on both clocks, and a small table of the playback rate (and the contact point's rate, as
// measured and as seen on screen) over the clip, a row wherever either has changed by a quarter.
std::vector<std::string> planLines(const ClipPlan& plan, const TimeWindow& window);

// The lines render's overlay shows after its own at frame k of `plan`: the slow motion or fast
// forward the frame plays at, or, in the landing's hold, that the landing is held.
std::vector<std::string> overlayExtraLines(const ClipPlan& plan, long k);

}  // namespace coinroll::pipeline
