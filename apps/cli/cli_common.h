#pragma once
/// \file cli_common.h
/// Shared plumbing of the `adaptex` command-line tool: every subcommand lives in its own cmd_*.cpp
/// and registers itself through an add_*_command() function called from main.cpp.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

namespace adaptex::cli {

/// Global state of one CLI run.
struct Context {
  bool quiet = false;  ///< --quiet: no progress / warnings on stderr.
  /// Prints a warning line to stderr unless quiet.
  void warn(const std::string& msg) const {
    if (!quiet) std::cerr << "adaptex: warning: " << msg << "\n";
  }
  /// Prints a progress/info line to stderr unless quiet.
  void info(const std::string& msg) const {
    if (!quiet) std::cerr << msg << "\n";
  }
};

void add_info_command(CLI::App& app, Context& ctx);
void add_unwrap_command(CLI::App& app, Context& ctx);
void add_paint_command(CLI::App& app, Context& ctx);
void add_eval_command(CLI::App& app, Context& ctx);
void add_strokes_command(CLI::App& app, Context& ctx);
void add_reparam_command(CLI::App& app, Context& ctx);
void add_demo_command(CLI::App& app, Context& ctx);

}  // namespace adaptex::cli
