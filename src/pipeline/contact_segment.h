#pragma once
// One contact mode's stretch of a HybridRun (hybrid_run.h): a Motion that may end in a transition
// (physics/contact_mode.h), handing the coin there to the mode physics::next names.

#include <optional>

#include "physics/contact_mode.h"
#include "pipeline/motion.h"

namespace coinroll::pipeline {

// A segment's end in a transition, and what it hands to the next mode.
struct SegmentEnd {
  physics::Transition transition = physics::Transition::SlideOnset;
  physics::Handover handover;
};

class ContactSegment : public Motion {
 public:
  // The transition that ended this segment; none while it runs or when a model event ended it.
  virtual std::optional<SegmentEnd> end() const = 0;
};

}  // namespace coinroll::pipeline
