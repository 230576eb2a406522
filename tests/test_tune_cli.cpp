// `snapfit tune` as a user runs it: the table of p50/p99 against m', the tuning file it
// saves, and progress bars that never run past their totals.
#include <doctest/doctest.h>
#include <filesystem>

#include "tests/progress_lines.h"
#include "tests/test_support.h"

using namespace snapfit;

TEST_CASE("tune cli: the sweep's table, the saved file, and progress within its totals") {
  const test::CacheDirScope cache;
  const test::Command c = test::run_command(std::string(SNAPFIT_CLI_PATH) + " tune " + SNAPFIT_SOURCE_DIR +
                                            "/scenes/default.json --repetitions 50");
  INFO(c.output);
  REQUIRE(c.status == 0);
  CHECK(c.output.find("variant 6dof energy force torque tricubic") != std::string::npos);
  // Saved when some m' fits; on a machine too busy for any, said and not kept.
  const std::size_t saved = c.output.find("saved to ");
  if (c.output.find("not saved: no m' fits the budget") != std::string::npos) {
    CHECK(saved == std::string::npos);
    const bool kept =
        std::filesystem::exists(cache.folder("tuning")) && !std::filesystem::is_empty(cache.folder("tuning"));
    CHECK(!kept);
  } else {
    REQUIRE(saved != std::string::npos);
    const std::string file = c.output.substr(saved + 9, c.output.find('\n', saved) - saved - 9);
    CHECK(std::filesystem::exists(file));
    CHECK(file.rfind(cache.dir.path.string(), 0) == 0);  // in the cache folder it was given
  }
  // The bars: the fields and spectra passes, and the sweep itself.
  CHECK(c.output.find("tuning") != std::string::npos);
  CHECK(c.output.find("% (") != std::string::npos);
  CHECK(test::overrun_bars(c.output).empty());
  // Every kernel it built (fields, spectra, the query) compiled without a compiler message.
  CHECK(c.output.find("with compiler messages") == std::string::npos);
  CHECK(c.output.find("warning") == std::string::npos);
}
