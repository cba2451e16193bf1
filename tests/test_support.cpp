#include "test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

namespace adaptex::test {

CliResult run_cli(const std::string& args, const std::string& shell_prefix) {
  TempDir tmp;
  const auto out = tmp.path / "out.txt", err = tmp.path / "err.txt";
  const std::string cmd = shell_prefix + "'" + ADAPTEX_CLI_PATH + "' " + args + " > '" + out.string() +
                          "' 2> '" + err.string() + "' < /dev/null";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  auto slurp = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

}  // namespace adaptex::test
