#pragma once
/// \file cli_common.h
/// Shared plumbing of the `adaptex` command-line tool: every subcommand lives in its own cmd_*.cpp
/// and registers itself through an add_*_command() function called from main.cpp.
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"

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

/// Writes \p text to \p path through \p out (committed with the rest of the command's outputs).
/// Every text output of the CLI (reports) goes through here, so a failed write is always an
/// OutputError (exit code 3), never bad input.
/// \throw OutputError the file cannot be created or written (permission denied, disk full).
inline void write_text(AtomicOutput& out, const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = out.add(path);
  std::ofstream f(tmp, std::ios::binary);
  if (!f) throw OutputError(path.string() + ": cannot open for writing");
  f << text;
  f.close();
  if (!f) throw OutputError(path.string() + ": write error (disk full?)");
}

void add_info_command(CLI::App& app, Context& ctx);
void add_unwrap_command(CLI::App& app, Context& ctx);
void add_paint_command(CLI::App& app, Context& ctx);
void add_eval_command(CLI::App& app, Context& ctx);
void add_strokes_command(CLI::App& app, Context& ctx);
void add_reparam_command(CLI::App& app, Context& ctx);
void add_shrink_command(CLI::App& app, Context& ctx);
void add_demo_command(CLI::App& app, Context& ctx);

/// Accepts a finite number >= 0 (CLI::NonNegativeNumber passes nan and inf, and its message prints
/// DBL_MAX in full).
inline const CLI::Validator kFiniteNonNegative(
    [](std::string& v) -> std::string {
      double x = 0;
      if (!CLI::detail::lexical_cast(v, x) || !std::isfinite(x) || x < 0) return "must be a finite number >= 0";
      return {};
    },
    "FINITE>=0");

}  // namespace adaptex::cli
