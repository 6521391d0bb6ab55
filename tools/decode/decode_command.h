#pragma once
/// @file
/// swlio-decode subcommands register themselves here, one source file per sensor format, so
/// adding a format does not touch main().

#include <CLI/CLI.hpp>

#include <functional>
#include <vector>

namespace swlio::tools {

/// Adds a subcommand to `app`; the callback it installs runs the command and sets the exit code.
using DecodeCommandFactory = std::function<void(CLI::App& app, int* exit_code)>;

/// All registered subcommand factories.
std::vector<DecodeCommandFactory>& DecodeCommands();

/// Registers a factory at static-initialization time: `static DecodeCommandRegistrar r(f);`.
struct DecodeCommandRegistrar {
  explicit DecodeCommandRegistrar(DecodeCommandFactory factory) {
    DecodeCommands().push_back(std::move(factory));
  }
};

}  // namespace swlio::tools
