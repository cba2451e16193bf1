// Placeholder: the `info` subcommand is being implemented; it reports that plainly.
#include "cli_common.h"
#include "adaptex/core/errors.h"

namespace adaptex::cli {

void add_info_command(CLI::App& app, Context&) {
  auto* sub = app.add_subcommand("info", "(not implemented yet)");
  sub->allow_extras();
  sub->callback([] { throw Error("'info' is not implemented yet"); });
}

}  // namespace adaptex::cli
