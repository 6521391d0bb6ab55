#pragma once
/// @file
/// The client side of the control protocol (protocol.h): connect to swliod's socket, send one
/// request, read the reply to EOF, all within one deadline. swlioctl is a thin shell around it.

#include <string>

#include "swlio/control/protocol.h"

namespace swlio::control {

/// Why a call got no reply. Each maps to one exit code of swlioctl (docs/control.md).
enum class CallError : uint8_t {
  kNone,
  kNoDaemon,    ///< no socket at the path, or nobody listens on it (ENOENT, ECONNREFUSED)
  kPermission,  ///< the socket's permissions refuse this user (EACCES, EPERM)
  kTimeout,     ///< no complete reply within the deadline
  kProtocol,    ///< the reply does not follow the protocol, or is larger than kMaxReplyBytes
  kIo,          ///< any other failure (path too long, socket errors)
};

struct CallResult {
  CallError error = CallError::kNone;
  std::string detail;  ///< what failed (error != kNone), for the user
  Reply reply;         ///< error == kNone
};

/// Sends `request` to the daemon listening at `socket_path` and waits for its reply, all within
/// `timeout_ms`.
CallResult Call(const std::string& socket_path, const Request& request, int timeout_ms);

}  // namespace swlio::control
