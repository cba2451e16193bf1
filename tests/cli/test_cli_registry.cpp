// The command line lists and runs the registered methods (adapt/method.h): a method registered from
// this test, with no edit in apps/cli, shows up in the help of `paint` and `reparam`, is accepted by
// their `--adapt` and runs, and its name is written to report.json.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/generate.h"
#include "adaptex/param/unwrap.h"
#include "cli_common.h"
#include "identity_method.h"
#include "test_support.h"

namespace adaptex {
namespace {

using test::IdentityMethod;

const bool registered = test::register_identity_method();

/// The `adaptex` command line as main.cpp builds it (quiet).
struct CommandLine {
  CLI::App app{"adaptex"};
  cli::Context ctx;
  CommandLine() {
    ctx.quiet = true;
    app.require_subcommand(1);
    cli::add_paint_command(app, ctx);
    cli::add_reparam_command(app, ctx);
  }
};

nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

TEST(CliRegistry, HelpListsARegisteredMethod) {
  ASSERT_TRUE(registered);
  CommandLine cl;
  for (const char* command : {"paint", "reparam"}) {
    const std::string help = cl.app.get_subcommand(command)->help();
    EXPECT_NE(help.find("identity (test: the identity warp)"), std::string::npos) << command << ":\n" << help;
    EXPECT_NE(help.find("density-flow ("), std::string::npos) << command << ":\n" << help;
  }
}

TEST(CliRegistry, PaintAndReparamRunARegisteredMethod) {
  ASSERT_TRUE(registered);
  test::TempDir dir;
  const TriMesh mesh = shapes::torus(24, 12);
  const Parameterization param = unwrap(mesh).param;
  write_obj(dir.path / "torus.obj", mesh, &param);
  GenerateOptions go;
  go.count = 2;
  write_strokes(dir.path / "strokes.json", generate_strokes(mesh, go));
  ImageRGBA8 texture(32, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      std::uint8_t* t = texture.texel(x, y);
      t[0] = static_cast<std::uint8_t>(8 * x), t[1] = static_cast<std::uint8_t>(8 * y), t[2] = 128, t[3] = 255;
    }
  write_png(dir.path / "texture.png", texture);

  const int computed = IdentityMethod::computed;
  CommandLine paint;
  paint.app.parse("paint " + (dir.path / "torus.obj").string() + " --strokes " + (dir.path / "strokes.json").string() +
                  " --size 64 --adapt identity -o " + (dir.path / "painted").string());
  EXPECT_EQ(IdentityMethod::computed, computed + 1);  // once, at the end
  const nlohmann::json painted = read_json(dir.path / "painted" / "report.json");
  EXPECT_EQ(painted["adapt"]["mode"], "identity");
  ASSERT_EQ(painted["adapt"]["reparameterizations"]["count"], 1);
  EXPECT_EQ(painted["adapt"]["reparameterizations"]["reports"][0]["mode"], "identity");

  CommandLine reparam;
  reparam.app.parse("reparam " + (dir.path / "torus.obj").string() + " " + (dir.path / "texture.png").string() +
                    " --adapt identity -o " + (dir.path / "reparam").string());
  EXPECT_EQ(IdentityMethod::computed, computed + 2);
  EXPECT_EQ(read_json(dir.path / "reparam" / "report.json")["adapt"]["mode"], "identity");

  // An unknown name is still refused, and the message lists the registered method.
  CommandLine bad;
  try {
    bad.app.parse("reparam " + (dir.path / "torus.obj").string() + " " + (dir.path / "texture.png").string() +
                  " --adapt swirl -o " + (dir.path / "bad").string());
    FAIL() << "no error for an unknown method";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("density-flow or identity"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path / "bad"));
}

}  // namespace
}  // namespace adaptex
