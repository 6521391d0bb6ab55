// swlioctl: swliod's control tool (docs/control.md), the chronyc/gpsd model: one request over
// the daemon's UNIX socket, the reply printed.
//
//   swlioctl [--socket PATH] [--timeout S] status
//   swlioctl [--socket PATH] [--timeout S] save-map PATH     (PATH and PATH.pcd, as swliod's user)
//   swlioctl [--socket PATH] [--timeout S] reset
//   swlioctl [--socket PATH] [--timeout S] relocalize X Y YAW_DEG [SIGMA_M]
//
// The reply's first line goes to stdout on success ("ok ..." without "ok"), to stderr on an
// error; the body (status) to stdout. Exit codes (sysexits.h), for scripts:
//   0  ok                      1  the daemon refused or the command failed
//   64 usage                   69 no daemon at the socket (EX_UNAVAILABLE)
//   75 timeout or busy (retry; EX_TEMPFAIL)   76 unexpected reply (EX_PROTOCOL)
//   77 permission denied (EX_NOPERM)          74 other I/O error (EX_IOERR)

#include <CLI/CLI.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "swlio/control/client.h"

namespace {

using swlio::control::CallError;
using swlio::control::Command;
using swlio::control::ReplyStatus;

constexpr int kExitRefused = 1;
constexpr int kExitUsage = 64;
constexpr int kExitNoDaemon = 69;
constexpr int kExitIo = 74;
constexpr int kExitTempFail = 75;
constexpr int kExitProtocol = 76;
constexpr int kExitNoPerm = 77;

int ExitCodeOf(CallError error) {
  switch (error) {
    case CallError::kNone:
      return 0;
    case CallError::kNoDaemon:
      return kExitNoDaemon;
    case CallError::kPermission:
      return kExitNoPerm;
    case CallError::kTimeout:
      return kExitTempFail;
    case CallError::kProtocol:
      return kExitProtocol;
    case CallError::kIo:
      return kExitIo;
  }
  return kExitIo;
}

int ExitCodeOf(ReplyStatus status) {
  switch (status) {
    case ReplyStatus::kOk:
      return 0;
    case ReplyStatus::kBusy:
    case ReplyStatus::kTimeout:
      return kExitTempFail;
    case ReplyStatus::kBadRequest:
      return kExitProtocol;  // swlioctl sent something this daemon does not read
    case ReplyStatus::kRefused:
    case ReplyStatus::kFailed:
      return kExitRefused;
  }
  return kExitRefused;
}

int Send(const std::string& socket, const swlio::control::Request& request, double timeout_s) {
  const auto result =
      swlio::control::Call(socket, request, static_cast<int>(std::lround(timeout_s * 1000.0)));
  if (result.error != CallError::kNone) {
    std::cerr << "swlioctl: " << result.detail << "\n";
    return ExitCodeOf(result.error);
  }
  const auto& reply = result.reply;
  if (reply.status != ReplyStatus::kOk) {
    std::cerr << "swlioctl: " << ToString(request.command) << ": " << ToString(reply.status) << ": "
              << reply.message << "\n";
    return ExitCodeOf(reply.status);
  }
  if (!reply.message.empty()) std::cout << reply.message << "\n";
  std::cout << reply.body;
  return 0;
}

int Main(int argc, char** argv) {
  CLI::App app{"swlioctl: control swliod over its UNIX socket (docs/control.md)"};
  app.require_subcommand(1);
  std::string socket = "/run/swlio/swliod.sock";
  double timeout_s = 70.0;
  app.add_option("--socket", socket, "the daemon's control socket (control.socket)")
      ->capture_default_str();
  app.add_option("--timeout", timeout_s,
                 "seconds to wait for the reply (save-map may take a while; the daemon answers "
                 "\"timeout\" after control.command_timeout_s)")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 3600.0));
  swlio::control::Request request;
  app.add_subcommand("status", "state, rates and health, as the health topic says them")
      ->callback([&] { request.command = Command::kStatus; });
  std::string map_path;
  CLI::App* save = app.add_subcommand(
      "save-map", "save the map being built to PATH and PATH.pcd (written by the daemon's user)");
  save->add_option("PATH", map_path, "map file (relative: from the current directory)")->required();
  save->callback([&] { request.command = Command::kSaveMap; });
  app.add_subcommand("reset", "re-initialize the estimator at its last good pose")->callback([&] {
    request.command = Command::kReset;
  });
  std::vector<double> pose;
  CLI::App* relocalize = app.add_subcommand(
      "relocalize",
      "tell the daemon where the robot is in the saved map: base_link at X Y (m) heading YAW "
      "(degrees, counter-clockwise from the map's x axis), within SIGMA (m, default 0.5)");
  relocalize->add_option("X Y YAW [SIGMA]", pose, "numbers")->required()->expected(3, 4);
  relocalize->callback([&] { request.command = Command::kRelocalize; });
  std::vector<std::string> note;
  CLI::App* mark = app.add_subcommand(
      "mark", "keep the last minutes as an incident of the black box (record.ring), with a note");
  mark->add_option("NOTE", note, "what the operator saw (words)");
  mark->callback([&] { request.command = Command::kMark; });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitUsage;
  }
  if (request.command == Command::kSaveMap) {
    // The daemon's working directory is not ours: send an absolute path.
    request.argument = std::filesystem::absolute(map_path).lexically_normal().string();
  }
  if (request.command == Command::kRelocalize) {
    std::ostringstream numbers;
    numbers.precision(17);
    for (size_t i = 0; i < pose.size(); ++i) numbers << (i > 0 ? " " : "") << pose[i];
    request.argument = numbers.str();
  }
  if (request.command == Command::kMark) {
    for (const std::string& word : note)
      request.argument += (request.argument.empty() ? "" : " ") + word;
  }
  return Send(socket, request, timeout_s);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& e) {  // std::bad_alloc, a filesystem error on the path
    std::cerr << "swlioctl: " << e.what() << "\n";
  }
  return kExitIo;
}
