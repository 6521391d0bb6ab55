#include "swlio/daemon/pipeline/hint_inbox.h"

#include <spdlog/spdlog.h>

#include "swlio/ipc/subscriber.h"

namespace swlio::daemon {

void HintInbox::Drain(const std::function<void(const PoseHint&)>& apply) {
  PoseHint hint;
  while (requests_.Pop(&hint)) {
    if (hint.command && hint.command->cancelled()) continue;
    apply(hint);
  }
  if (reader_ == nullptr) return;
  for (const auto& received : reader_->TakePoses()) {
    std::string error;
    const std::optional<PoseHint> h = HintFromInitialPose(received.msg, map_frame_, &error);
    if (h) {
      apply(*h);
      continue;
    }
    unreadable_.fetch_add(1, std::memory_order_relaxed);
    spdlog::warn("pose hint: /initialpose ignored: {}", error);
  }
}

void HintInbox::FailQueued() {
  PoseHint hint;
  while (requests_.Pop(&hint)) {
    if (hint.command)
      hint.command->Finish({control::ReplyStatus::kFailed, "the daemon stopped", {}});
  }
}

}  // namespace swlio::daemon
