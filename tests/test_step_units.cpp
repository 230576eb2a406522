// The length units of a STEP file (io/step_units.h): SI length units found in their
// entities however they are spread over lines, other units left to OpenCASCADE.
#include <doctest/doctest.h>

#include "io/step_units.h"
#include "tests/test_support.h"

using namespace snapfit;

TEST_CASE("step units: the SI length units of a file, and which are refused") {
  const std::string text =
      "#10 = ( LENGTH_UNIT() NAMED_UNIT(*)\n  SI_UNIT( .MILLI., .METRE. ) );\n"
      "#11 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );\n"
      "#12 = ( CONVERSION_BASED_UNIT('INCH',#13) LENGTH_UNIT() NAMED_UNIT(#14) );\n"
      "#15 = (length_unit() named_unit(*) si_unit($,.metre.));\n";
  const std::vector<std::string> units = step_si_length_units(text);
  REQUIRE(units.size() == 2);
  CHECK(units[0] == "SI_UNIT(.MILLI.,.METRE.)");
  CHECK(units[1] == "si_unit($,.metre.)");

  const test::TempDir dir;
  test::write_text(dir.file("ok.step"), text);
  CHECK(step_length_unit_problem(dir.file("ok.step")).empty());
  test::write_text(dir.file("furlong.step"), "#1 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.FURLONG.) );\n");
  CHECK(step_length_unit_problem(dir.file("furlong.step")).find("SI_UNIT(.MILLI.,.FURLONG.)") != std::string::npos);
  test::write_text(dir.file("prefix.step"), "#1 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLIS.,.METRE.) );\n");
  CHECK(step_length_unit_problem(dir.file("prefix.step")).find("unknown prefix") != std::string::npos);
}
