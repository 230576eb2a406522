#pragma once
// 2D slices of grid fields as colour-mapped PNG images, written with libpng (the public
// declarations: include/snapfit/slice_image.h).
#include "snapfit/slice_image.h"
