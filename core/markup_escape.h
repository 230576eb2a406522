#pragma once
// Text inside XML or HTML: the five characters with a meaning there as their entities
// (escape_markup, public in include/snapfit/export.h).
#include "snapfit/export.h"
