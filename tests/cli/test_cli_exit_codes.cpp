// Exit codes of the CLI (issue 11, docs/reliability.md): an output that cannot be written exits 3
// (OutputError, "cannot write output: ..."), never 2 (bad input), for every kind of output the CLI
// writes (mesh, report, images, stroke files, directories, standard output), and leaves no partial
// output behind. Out-of-range option values (`unwrap --layout-size`) are bad input: exit 2.
// The tests run as any user (root too): unwritable places are /proc (no file can be created there),
// a path below a regular file, and an output path that is an existing directory.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "test_support.h"

namespace adaptex {
namespace {

using test::run_cli;
using test::TempDir;

std::string q(const std::filesystem::path& p) {
  std::string s(1, '\'');
  s += p.string();
  s += '\'';
  return s;
}

/// A directory no file can be created in, even by root.
const std::filesystem::path kNoDir = "/proc/adaptex-no-such-dir";

/// `adaptex ARGS` must exit 3 with one "cannot write output" line naming \p what.
void expect_output_error(const std::string& args, const std::string& what) {
  const auto r = run_cli("-q " + args);
  EXPECT_EQ(r.exit_code, 3) << args << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("adaptex: error: cannot write output: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << "expected '" << what << "' in: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

/// Every regular file under \p dir (recursively), as paths relative to it, sorted.
std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.push_back(std::filesystem::relative(e.path(), dir).string());
  std::sort(out.begin(), out.end());
  return out;
}

struct CliExitCodes : ::testing::Test {
  TempDir dir;
  std::filesystem::path mesh;
  void SetUp() override {
    mesh = dir.path / "ball.obj";
    write_obj(mesh, shapes::sphere(12, 6), nullptr);
  }
};

TEST_F(CliExitCodes, UnwrapReportThatCannotBeWrittenExitsThreeAndWritesNothing) {
  const auto out = dir.path / "u.obj";
  expect_output_error("unwrap " + q(mesh) + " -o " + q(out) + " --report " + q(kNoDir / "r.json"),
                      kNoDir.string());
  // A report path below a regular file, and a report path that is a directory.
  expect_output_error("unwrap " + q(mesh) + " -o " + q(out) + " --report " + q(mesh / "r.json"),
                      (mesh / "r.json").string());
  std::filesystem::create_directory(dir.path / "rdir");
  expect_output_error("unwrap " + q(mesh) + " -o " + q(out) + " --report " + q(dir.path / "rdir"),
                      "is a directory");
  // All or nothing: the OBJ, written before the report, was not committed either.
  EXPECT_EQ(files_in(dir.path), std::vector<std::string>{"ball.obj"});
}

TEST_F(CliExitCodes, UnwrapMeshAndLayoutThatCannotBeWrittenExitThree) {
  expect_output_error("unwrap " + q(mesh) + " -o " + q(kNoDir / "u.obj"), kNoDir.string());
  expect_output_error("unwrap " + q(mesh) + " -o " + q(dir.path / "u.obj") + " --layout " +
                          q(kNoDir / "l.png"),
                      kNoDir.string());
  EXPECT_EQ(files_in(dir.path), std::vector<std::string>{"ball.obj"});
}

TEST_F(CliExitCodes, StrokeFilesThatCannotBeWrittenExitThree) {
  expect_output_error("strokes generate " + q(mesh) + " --count 2 -o " + q(kNoDir / "s.json"),
                      kNoDir.string());
  const auto strokes = dir.path / "s.json";
  ASSERT_EQ(run_cli("-q strokes generate " + q(mesh) + " --count 2 -o " + q(strokes)).exit_code, 0);
  expect_output_error("strokes check " + q(strokes) + " -o " + q(strokes / "n.json"),
                      (strokes / "n.json").string());
  EXPECT_EQ(files_in(dir.path), (std::vector<std::string>{"ball.obj", "s.json"}));
}

TEST_F(CliExitCodes, PaintReparamAndDemoOutputDirectoriesThatCannotBeCreatedExitThree) {
  const auto strokes = dir.path / "s.json";
  ASSERT_EQ(run_cli("-q strokes generate " + q(mesh) + " --count 2 -o " + q(strokes)).exit_code, 0);
  expect_output_error("paint " + q(mesh) + " --strokes " + q(strokes) + " --size 64 -o " + q(kNoDir),
                      kNoDir.string());
  // A painted textured mesh to re-parameterize.
  const auto painted = dir.path / "painted";
  const auto p = run_cli("-q paint " + q(mesh) + " --strokes " + q(strokes) + " --size 64 -o " + q(painted));
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const auto obj = painted / "ball.obj", png = painted / "ball.png";
  expect_output_error("reparam " + q(obj) + " " + q(png) + " -o " + q(kNoDir), kNoDir.string());
  expect_output_error("reparam " + q(obj) + " " + q(png) + " -o " + q(dir.path / "r") + " --debug-maps " +
                          q(kNoDir / "maps"),
                      kNoDir.string());
  expect_output_error("demo -o " + q(kNoDir / "demo"), kNoDir.string());
  EXPECT_FALSE(std::filesystem::exists(dir.path / "r" / "report.json"));
}

/// Runs the CLI with stdout on /dev/full (every write fails with ENOSPC); returns (exit code, stderr).
std::pair<int, std::string> run_to_dev_full(const std::string& args) {
  TempDir tmp;
  const auto err = tmp.path / "err.txt";
  const std::string cmd = std::string("'") + ADAPTEX_CLI_PATH + "' -q " + args + " > /dev/full 2> " + q(err);
  const int status = std::system(cmd.c_str());
  std::ifstream in(err);
  std::stringstream ss;
  ss << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

TEST_F(CliExitCodes, ReportOnAFullStandardOutputExitsThree) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "/dev/full not available";
  const auto [code, err] = run_to_dev_full("info " + q(mesh) + " --json");
  EXPECT_EQ(code, 3) << err;
  EXPECT_NE(err.find("cannot write output: standard output"), std::string::npos) << err;
  // The same command with a writable stdout succeeds: the failure is the output's, not the input's.
  EXPECT_EQ(run_cli("-q info " + q(mesh) + " --json").exit_code, 0);
}

TEST_F(CliExitCodes, LayoutSizeOutOfRangeIsBadInput) {
  const auto out = dir.path / "u.obj", lay = dir.path / "l.png";
  for (const std::string bad : {"15", "8193", "100000", "-1", "abc"}) {
    const auto r = run_cli("-q unwrap " + q(mesh) + " -o " + q(out) + " --layout " + q(lay) +
                           " --layout-size " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_EQ(r.err.rfind("adaptex: error: --layout-size", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("16 to 8192"), std::string::npos) << r.err;  // says the valid range
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(files_in(dir.path), std::vector<std::string>{"ball.obj"});
  // The lower end is accepted and gives a 16 x 16 PNG (the upper end, 8192, is not run: 256 MB).
  const auto r = run_cli("-q unwrap " + q(mesh) + " -o " + q(out) + " --layout " + q(lay) + " --layout-size 16");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageRGBA8 img = read_image(lay);
  EXPECT_EQ(img.width, 16);
  EXPECT_EQ(img.height, 16);
}

TEST_F(CliExitCodes, ReparamBadGridAndWeightsAreBadInput) {
  // The options are checked before the files are read (the mesh stands in for the texture here).
  const std::string base = "-q reparam " + q(mesh) + " " + q(mesh) + " -o " + q(dir.path / "r");
  for (const std::string bad : {"--grid ''", "--grid ' 16'", "--grid 256,16", "--grid 16,", "--alpha inf",
                                "--beta nan", "--alpha -1"}) {
    const auto r = run_cli(base + " " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_NE(r.err.find(bad.substr(0, 6)), std::string::npos) << r.err;  // names the option
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(files_in(dir.path), std::vector<std::string>{"ball.obj"});
}

TEST_F(CliExitCodes, PaintBadMinGainIsBadInputAndWritesNothing) {
  const auto strokes = dir.path / "s.json";
  ASSERT_EQ(run_cli("-q strokes generate " + q(mesh) + " --count 2 -o " + q(strokes)).exit_code, 0);
  const std::string base = "-q paint " + q(mesh) + " --strokes " + q(strokes) + " --size 32 --reparam each-stroke -o " +
                           q(dir.path / "p");
  for (const std::string bad : {"--min-gain -1", "--min-gain nan", "--min-gain inf", "--min-gain x"}) {
    const auto r = run_cli(base + " " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_NE(r.err.find("--min-gain"), std::string::npos) << r.err;  // names the option
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(files_in(dir.path), (std::vector<std::string>{"ball.obj", "s.json"}));
  // A good value is taken and written to report.json.
  const auto r = run_cli(base + " --min-gain 0.25");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(dir.path / "p" / "report.json");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("\"min_gain_db\": 0.25"), std::string::npos);
  EXPECT_NE(ss.str().find("\"surface_cache_samples\": "), std::string::npos);  // what the session used
}

}  // namespace
}  // namespace adaptex
