// variant_name (include/snapfit/query.h): a variant in words, as tuning files and
// reports name it.
#include <string>

#include "snapfit/query.h"

namespace snapfit {

std::string variant_name(const QueryVariant& v) {
  std::string name = v.translation_only ? "translation" : "6dof";
  name += " energy";
  if (v.force) name += " force";
  if (v.torque) name += " torque";
  if (v.translation_only) return name;
  if (v.rotation == RotationMethod::exact_product)
    name += v.product_update == ProductUpdate::background ? " exact-product background" : " exact-product each-query";
  else
    name += v.interpolation == Interpolation::tricubic ? " tricubic" : " trilinear";
  if (v.near_far) name += " near-far";
  return name;
}

}  // namespace snapfit
