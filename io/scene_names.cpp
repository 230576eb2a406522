// The names of a scene's enums (include/snapfit/scene.h): one table each, as scene files,
// the tool and reports spell them.
#include "core/name_table.h"
#include "snapfit/scene.h"

namespace snapfit {

namespace {

const std::pair<Method, const char*> kMethods[] = {
    {Method::snapfit, "snapfit"}, {Method::vps, "vps"}, {Method::vps_hybrid, "vps_hybrid"}};
const std::pair<Motion, const char*> kMotions[] = {{Motion::translation, "translation"}, {Motion::six_dof, "6dof"}};
const std::pair<DescriptorKind, const char*> kDescriptorKinds[] = {{DescriptorKind::skeletal_density, "skeletal_density"},
                                                                   {DescriptorKind::indicator, "indicator"}};
const std::pair<SpectrumSource, const char*> kSpectrumSources[] = {{SpectrumSource::grid, "grid"},
                                                                   {SpectrumSource::spheres, "spheres"}};
const std::pair<HybridRegion, const char*> kHybridRegions[] = {{HybridRegion::pair, "pair"}, {HybridRegion::face, "face"}};

}  // namespace

const char* method_name(Method m) { return name_in(kMethods, m); }
std::optional<Method> method_named(const std::string& name) { return value_in(kMethods, name); }
std::string method_names() { return names_in(kMethods); }

const char* motion_name(Motion m) { return name_in(kMotions, m); }
std::optional<Motion> motion_named(const std::string& name) { return value_in(kMotions, name); }
std::string motion_names() { return names_in(kMotions); }

const char* descriptor_kind_name(DescriptorKind k) { return name_in(kDescriptorKinds, k); }
std::optional<DescriptorKind> descriptor_kind_named(const std::string& name) {
  return value_in(kDescriptorKinds, name);
}
std::string descriptor_kind_names() { return names_in(kDescriptorKinds); }

const char* spectrum_source_name(SpectrumSource s) { return name_in(kSpectrumSources, s); }
std::optional<SpectrumSource> spectrum_source_named(const std::string& name) {
  return value_in(kSpectrumSources, name);
}
std::string spectrum_source_names() { return names_in(kSpectrumSources); }

const char* hybrid_region_name(HybridRegion r) { return name_in(kHybridRegions, r); }
std::optional<HybridRegion> hybrid_region_named(const std::string& name) { return value_in(kHybridRegions, name); }
std::string hybrid_region_names() { return names_in(kHybridRegions); }

}  // namespace snapfit
