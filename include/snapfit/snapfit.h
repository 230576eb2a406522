#pragma once
// snapfit: haptic guidance for assembling rigid parts (seed 000's skeletal densities and
// truncated Fourier sums) on any OpenCL device. The whole public API:
//   scene.h          scenes: parts, poses, descriptor, grid and haptics parameters, load_scene
//   assembly.h       a scene's parts on a device with fields and spectra precomputed (cached)
//   query.h          energy, force and torque of part 2 at a pose, per frame, truncated to m' modes
//   tuning.h         m' for the scene's frame budget on this device (auto_tune)
//   haptic_device.h  what a haptic device implements (read pose, send wrench, limits)
//   haptic_loop.h    the fixed-rate loop with virtual coupling, on its own thread
//   pose.h, error.h  rigid poses; the one exception type
#include "snapfit/assembly.h"
#include "snapfit/error.h"
#include "snapfit/haptic_device.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/pose.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"
#include "snapfit/tuning.h"
