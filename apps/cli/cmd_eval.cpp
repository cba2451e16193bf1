// Placeholder: the `eval` subcommand is being implemented; it reports that plainly.
#include "cli_common.h"
#include "adaptex/core/errors.h"

namespace adaptex::cli {

void add_eval_command(CLI::App& app, Context&) {
  auto* sub = app.add_subcommand("eval", "(not implemented yet)");
  sub->allow_extras();
  sub->callback([] { throw Error("'eval' is not implemented yet"); });
}

}  // namespace adaptex::cli
