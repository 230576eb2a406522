#pragma once
// A mesh cut by an axis-aligned plane: the outline a slice image of a field draws over
// it (mesh_slice_outline, public in include/snapfit/mesh.h).
#include "snapfit/mesh.h"
