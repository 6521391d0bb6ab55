#pragma once
/// @file
/// This build's version: "0.1.0 (git 1a2b3c4d5e6f)", or without the git part outside a
/// checkout. Incidents carry it; swlio-replay compares it.

#include <string>

namespace swlio::daemon {

std::string SwlioVersion();

}  // namespace swlio::daemon
