#pragma once
// A part's boundary as one triangle soup, in scene length units (the public type,
// include/snapfit/mesh.h).
#include "snapfit/mesh.h"
