// The names of a scene's enums (include/snapfit/scene.h): one table each, as scene files,
// the tool and reports spell them.
#include "core/name_table.h"
#include "snapfit/scene.h"

namespace snapfit {

namespace {

const std::pair<Method, const char*> kMethods[] = {
    {Method::snapfit, "snapfit"}, {Method::vps, "vps"}, {Method::vps_hybrid, "vps_hybrid"}};
const std::pair<Motion, const char*> kMotions[] = {{Motion::translation, "translation"}, {Motion::six_dof, "6dof"}};

}  // namespace

const char* method_name(Method m) { return name_in(kMethods, m); }
std::optional<Method> method_named(const std::string& name) { return value_in(kMethods, name); }
std::string method_names() { return names_in(kMethods); }

const char* motion_name(Motion m) { return name_in(kMotions, m); }
std::optional<Motion> motion_named(const std::string& name) { return value_in(kMotions, name); }
std::string motion_names() { return names_in(kMotions); }

}  // namespace snapfit
