#pragma once
// Order statistics of timing samples (quantile, public in include/snapfit/quantile.h).
#include "snapfit/quantile.h"
