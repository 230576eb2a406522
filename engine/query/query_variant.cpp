// The names of interpolations, strategies and variants (include/snapfit/query.h): one
// table each, as scenes, the tool, tuning and strategy files and reports spell them.
#include <cstddef>
#include <string>
#include <utility>

#include "core/name_table.h"
#include "snapfit/query.h"

namespace snapfit {

namespace {

const std::pair<Interpolation, const char*> kInterpolations[] = {{Interpolation::trilinear, "trilinear"},
                                                                 {Interpolation::tricubic, "tricubic"}};
const std::pair<QueryStrategy, const char*> kStrategies[] = {{QueryStrategy::tricubic, "tricubic"},
                                                             {QueryStrategy::trilinear, "trilinear"},
                                                             {QueryStrategy::exact_product, "exact-product"},
                                                             {QueryStrategy::near_far, "near-far"}};

}  // namespace

const char* interpolation_name(Interpolation interpolation) { return name_in(kInterpolations, interpolation); }

std::optional<Interpolation> interpolation_named(const std::string& name) { return value_in(kInterpolations, name); }

const std::vector<QueryStrategy>& query_strategies() {
  static const std::vector<QueryStrategy> all = [] {
    std::vector<QueryStrategy> v;
    for (const auto& entry : kStrategies) v.push_back(entry.first);
    return v;
  }();
  return all;
}

const char* strategy_name(QueryStrategy strategy) { return name_in(kStrategies, strategy); }

std::optional<QueryStrategy> strategy_named(const std::string& name) { return value_in(kStrategies, name); }

QueryVariant with_strategy(QueryVariant v, QueryStrategy strategy, ProductUpdate update) {
  if (v.translation_only) return v;
  v.interpolation = strategy == QueryStrategy::trilinear ? Interpolation::trilinear : Interpolation::tricubic;
  v.rotation = RotationMethod::interpolated;
  v.near_far = false;
  if (strategy == QueryStrategy::exact_product || strategy == QueryStrategy::near_far) {
    v.rotation = RotationMethod::exact_product;
    v.product_update = update;
    v.near_far = strategy == QueryStrategy::near_far;
  }
  return v;
}

std::string variant_name(const QueryVariant& v) {
  std::string name = v.translation_only ? "translation" : "6dof";
  name += " energy";
  if (v.force) name += " force";
  if (v.torque) name += " torque";
  if (v.translation_only) return name;
  if (v.rotation == RotationMethod::exact_product)
    name += v.product_update == ProductUpdate::background ? " exact-product background" : " exact-product each-query";
  else
    name += std::string(" ") + interpolation_name(v.interpolation);
  if (v.near_far) name += " near-far";
  return name;
}

}  // namespace snapfit
