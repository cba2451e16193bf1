// adaptex command-line tool. Exit codes: 0 success, 2 bad input (one line on stderr, no partial
// output), 3 an output could not be written, 4 out of memory, 1 internal failure.
#include <exception>
#include <new>
#include <iostream>
#include <string_view>

#include "adaptex/core/allocator.h"
#include "adaptex/core/errors.h"
#include "cli_common.h"

namespace {

/// The subcommand of the command line: its first argument that is not an option (the global
/// options take no values), or "" when there is none.
std::string_view subcommand_of(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (argv[i][0] != '-') return argv[i];
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  // The commands that unwrap a mesh allocate small blocks in every thread: per-thread heaps
  // (docs/decisions.md, "Scans: unwrap and paint allocate from per-thread heaps").
  const std::string_view command = subcommand_of(argc, argv);
  adaptex::keep_freed_memory_in_process_unless_disabled(command == "unwrap" || command == "paint"
                                                            ? adaptex::ArenaPolicy::PerThread
                                                            : adaptex::ArenaPolicy::Shared);
  CLI::App app{"adaptex: signal-adaptive parameterization for painting on 3-D meshes"};
  app.require_subcommand(1);
  adaptex::cli::Context ctx;
  app.add_flag("-q,--quiet", ctx.quiet, "No progress or warning lines on stderr");
  app.set_version_flag("--version", "adaptex " ADAPTEX_VERSION);
  adaptex::cli::add_info_command(app, ctx);
  adaptex::cli::add_unwrap_command(app, ctx);
  adaptex::cli::add_paint_command(app, ctx);
  adaptex::cli::add_eval_command(app, ctx);
  adaptex::cli::add_strokes_command(app, ctx);
  adaptex::cli::add_reparam_command(app, ctx);
  adaptex::cli::add_shrink_command(app, ctx);
  adaptex::cli::add_demo_command(app, ctx);
  try {
    app.parse(argc, argv);
    // Reports printed on stdout (`info --json`, `eval`) are outputs too: a failed write is exit 3.
    std::cout.flush();
    if (!std::cout) throw adaptex::OutputError("standard output: write error (closed pipe or disk full?)");
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, exit code 2, like every other bad input.
    std::cerr << "adaptex: error: " << e.what() << " (see --help)\n";
    return 2;
  } catch (const adaptex::CancelledError& e) {
    std::cerr << "adaptex: error: cancelled\n";
    return 1;
  } catch (const adaptex::InvalidInputError& e) {
    std::cerr << "adaptex: error: " << e.what() << "\n";
    return 2;
  } catch (const adaptex::OutputError& e) {
    std::cerr << "adaptex: error: cannot write output: " << e.what() << "\n";
    return 3;
  } catch (const std::bad_alloc&) {
    std::cerr << "adaptex: error: out of memory (the input is too large for the memory available)\n";
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "adaptex: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
