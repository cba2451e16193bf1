// Placeholder: the `paint` subcommand is being implemented; it reports that plainly.
#include "cli_common.h"
#include "adaptex/core/errors.h"

namespace adaptex::cli {

void add_paint_command(CLI::App& app, Context&) {
  auto* sub = app.add_subcommand("paint", "(not implemented yet)");
  sub->allow_extras();
  sub->callback([] { throw Error("'paint' is not implemented yet"); });
}

}  // namespace adaptex::cli
