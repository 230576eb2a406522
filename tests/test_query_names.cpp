// The one table of names for interpolations and query strategies (include/snapfit/query.h
// interpolation_name, strategy_named, with_strategy): every name round-trips, an unknown
// one is refused, and each strategy makes the variant it names.
#include <doctest/doctest.h>

#include "snapfit/query.h"

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
