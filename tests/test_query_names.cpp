// The one table of names for interpolations and query strategies (include/snapfit/query.h
// interpolation_name, strategy_named, with_strategy), methods and motions
// (include/snapfit/scene.h) and map FFTs (engine/maps/map_fft.h): every name round-trips,
// an unknown one is refused, and each strategy makes the variant it names.
#include <doctest/doctest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/maps/map_fft.h"
#include "snapfit/error.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"
#include "tests/test_support.h"

using namespace snapfit;

TEST_CASE("query names: interpolations and strategies round-trip, unknown names are refused") {
  for (Interpolation i : {Interpolation::trilinear, Interpolation::tricubic})
    CHECK(interpolation_named(interpolation_name(i)) == i);
  CHECK_FALSE(interpolation_named("cubic"));
  REQUIRE(query_strategies().size() == 4);
  for (QueryStrategy s : query_strategies()) CHECK(strategy_named(strategy_name(s)) == s);
  CHECK(std::string(strategy_name(QueryStrategy::exact_product)) == "exact-product");
  CHECK_FALSE(strategy_named("auto"));
  CHECK_FALSE(strategy_named("exact product"));
}

TEST_CASE("query names: each strategy makes the variant it names") {
  QueryVariant base;  // a 6-DOF variant
  base.interpolation = Interpolation::tricubic;
  const QueryVariant trilinear = with_strategy(base, QueryStrategy::trilinear, ProductUpdate::background);
  CHECK(trilinear.interpolation == Interpolation::trilinear);
  CHECK(trilinear.rotation == RotationMethod::interpolated);
  const QueryVariant exact = with_strategy(base, QueryStrategy::exact_product, ProductUpdate::background);
  CHECK(exact.rotation == RotationMethod::exact_product);
  CHECK(exact.product_update == ProductUpdate::background);
  CHECK_FALSE(exact.near_far);
  const QueryVariant split = with_strategy(base, QueryStrategy::near_far, ProductUpdate::each_query);
  CHECK(split.near_far);
  CHECK(split.product_update == ProductUpdate::each_query);
  CHECK(variant_name(split) == "6dof energy force torque exact-product each-query near-far");
  // Back from the exact product to an interpolated strategy: nothing of it is left.
  const QueryVariant back = with_strategy(split, QueryStrategy::tricubic, ProductUpdate::background);
  CHECK(back.rotation == RotationMethod::interpolated);
  CHECK_FALSE(back.near_far);
  CHECK(variant_name(back) == "6dof energy force torque tricubic");
  // A translation-only variant has only its lines.
  QueryVariant lines;
  lines.translation_only = true;
  CHECK(variant_name(with_strategy(lines, QueryStrategy::near_far, ProductUpdate::background)) == variant_name(lines));
}

TEST_CASE("scene and map names: methods, motions and map FFTs round-trip, and scenes name the tables choices") {
  for (Method m : {Method::snapfit, Method::vps, Method::vps_hybrid}) CHECK(method_named(method_name(m)) == m);
  CHECK(std::string(method_name(Method::vps_hybrid)) == "vps_hybrid");
  CHECK_FALSE(method_named("voxmap"));
  CHECK(method_names() == "snapfit, vps or vps_hybrid");
  for (Motion m : {Motion::translation, Motion::six_dof}) CHECK(motion_named(motion_name(m)) == m);
  CHECK(std::string(motion_name(Motion::six_dof)) == "6dof");
  CHECK_FALSE(motion_named("6-dof"));
  CHECK(motion_names() == "translation or 6dof");
  for (MapFft f : map_ffts_built()) CHECK(parse_map_fft(map_fft_name(f)) == f);
  CHECK_THROWS_WITH_AS(parse_map_fft("cufft"), "unknown map FFT 'cufft' (expected clfft, fftw or vkfft)", Error);

  // The scene reader's messages list the table's names; the writer spells them so.
  const std::string origin = std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json";
  std::ifstream in(origin);
  nlohmann::json j = nlohmann::json::parse(in);
  j["motion"] = "6-dof";
  CHECK(test::error_of([&] { parse_scene(j.dump(), origin); }).find("(expected translation or 6dof)") !=
        std::string::npos);
  j["motion"] = "6dof";
  j["method"] = "voxmap";
  CHECK(test::error_of([&] { parse_scene(j.dump(), origin); }).find("(expected snapfit, vps or vps_hybrid)") !=
        std::string::npos);
  j["method"] = "vps_hybrid";
  const nlohmann::json written = nlohmann::json::parse(scene_to_json(parse_scene(j.dump(), origin)));
  CHECK(written["method"] == "vps_hybrid");
  CHECK(written["motion"] == "6dof");
}
