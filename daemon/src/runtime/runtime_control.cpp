// Runtime as the control thread's target (control_server.h, docs/control.md): status from the
// health snapshot and the health message published last; save-map to the loop-closure thread,
// which owns the pose graph; reset to the optimizer thread, which owns the estimator; mark to
// the black box (record.ring).

#include <spdlog/spdlog.h>

#include "swlio/daemon/control/status_report.h"
#include "swlio/daemon/pipeline/pose_hint.h"
#include "swlio/daemon/runtime/event_log.h"
#include "swlio/daemon/runtime/runtime.h"

namespace swlio::daemon {

using control::Reply;
using control::ReplyStatus;

void Runtime::OpenControl() {
  if (config_.control.socket.empty()) {
    spdlog::info("control: off (control.socket is empty)");
    return;
  }
  std::string error, warning;
  control_ = ControlServer::Listen(config_.control, this, &error, &warning);
  if (!control_) {
    spdlog::warn(
        "control: cannot listen on {}: {}; running without control (swlioctl). Set "
        "control.socket to a writable path, or \"\" to turn it off (docs/control.md)",
        config_.control.socket, error);
    return;
  }
  if (!warning.empty()) spdlog::warn("control: {}", warning);
  spdlog::info("control: listening on {} (swlioctl --socket {})", control_->path(),
               control_->path());
}

std::optional<ipc::DiagnosticArray> Runtime::LastHealth() const {
  std::lock_guard<std::mutex> lock(health_mutex_);
  return last_health_;
}

std::string Runtime::Status() {
  StatusFacts facts;
  facts.mode = localization_ ? "localizing" : loop_closure_ ? "mapping" : "odometry";
  facts.ready = Ready();
  return StatusReport(Snapshot(), facts, LastHealth());
}

std::shared_ptr<PendingCommand> Runtime::Mark(std::shared_ptr<PendingCommand> command,
                                              Reply* refusal) {
  if (!recorder_ || recorder_->incidents() == nullptr) {
    *refusal = Reply{ReplyStatus::kRefused,
                     "the black box is off (record.ring" +
                         std::string(blackbox_error_.empty() ? ")" : ": " + blackbox_error_ + ")"),
                     ""};
    return nullptr;
  }
  const int64_t now = MonotonicNowNs();
  const std::string note = command->request().argument;
  IncidentEvent e{time_.ToDaemon(now), now + stamp_clock_->counters().offset_ns, "mark",
                  note.empty() ? "marked by an operator" : "operator: " + note};
  LogEvent(spdlog::level::warn, "incident", "incident: mark: " + e.detail,
           {{"REASON", "mark"}, {"DETAIL", e.detail}});
  recorder_->AddEvent(std::move(e));
  command->Finish(Reply{ReplyStatus::kOk,
                        "marked: the incident keeps " +
                            std::to_string(static_cast<int>(config_.record.incident_before_s)) +
                            " s before to " +
                            std::to_string(static_cast<int>(config_.record.incident_after_s)) +
                            " s after now, under " + config_.record.directory + "/incidents",
                        ""});
  return command;
}

std::shared_ptr<PendingCommand> Runtime::Submit(const control::Request& request, Reply* refusal) {
  auto command = std::make_shared<PendingCommand>(request);
  auto refuse = [refusal](ReplyStatus status, std::string message) {
    *refusal = Reply{status, std::move(message), ""};
    return nullptr;
  };
  switch (request.command) {
    case control::Command::kSaveMap:
      if (localization_) {
        return refuse(ReplyStatus::kRefused, "localizing in the fixed map " +
                                                 config_.map.load_path +
                                                 " (map.localize): no map is being built");
      }
      if (!loop_closure_) {
        return refuse(ReplyStatus::kRefused,
                      "loop closure is off (estimator.loop_closure.enabled, or estimator.mode "
                      "lidar-only): there is no pose graph to save");
      }
      if (!loop_closure_->RequestSave(command))
        return refuse(ReplyStatus::kBusy, "earlier save-map requests are still queued");
      return command;
    case control::Command::kReset:
      if (ModeFromConfig(config_) != EstimatorMode::kTightlyCoupled) {
        return refuse(ReplyStatus::kRefused,
                      "reset re-initializes the tightly coupled window; estimator.mode is "
                      "lidar-only");
      }
      if (!optimizer_->RequestReset(command))
        return refuse(ReplyStatus::kBusy, "earlier reset requests are still queued");
      return command;
    case control::Command::kRelocalize: {
      if (!localization_ && !loop_closure_) {
        return refuse(ReplyStatus::kRefused,
                      "relocalize needs a map frame: localizing in a saved map (map.localize) "
                      "or loop closure while mapping");
      }
      std::string error;
      std::optional<PoseHint> hint = HintFromArgument(request.argument, &error);
      if (!hint) return refuse(ReplyStatus::kBadRequest, error);
      hint->command = command;
      const bool queued = localization_ ? localization_->RequestHint(std::move(*hint))
                                        : loop_closure_->RequestHint(std::move(*hint));
      if (!queued)
        return refuse(ReplyStatus::kBusy, "earlier relocalize requests are still queued");
      return command;
    }
    case control::Command::kMark:
      return Mark(command, refusal);
    case control::Command::kStatus:
      break;
  }
  return refuse(ReplyStatus::kBadRequest, "status is answered directly");
}

}  // namespace swlio::daemon
