// Placeholder: the `unwrap` subcommand is being implemented; it reports that plainly.
#include "cli_common.h"
#include "adaptex/core/errors.h"

namespace adaptex::cli {

void add_unwrap_command(CLI::App& app, Context&) {
  auto* sub = app.add_subcommand("unwrap", "(not implemented yet)");
  sub->allow_extras();
  sub->callback([] { throw Error("'unwrap' is not implemented yet"); });
}

}  // namespace adaptex::cli
