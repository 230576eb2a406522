#pragma once
// snapfit: haptic guidance for assembling rigid parts (Behandish & Ilies 2016's skeletal densities and
// truncated Fourier sums) on any OpenCL device. The whole public API:
//   scene.h          scenes: parts, poses, descriptor, grid and haptics parameters, load_scene
//   assembly.h       a scene's parts on a device with fields and spectra precomputed (cached)
//   query.h          energy, force and torque of part 2 at a pose, per frame, truncated to m' modes
//   tuning.h         m' for the scene's frame budget on this device (auto_tune)
//   haptic_device.h  what a haptic device implements (read pose, send wrench, limits)
//   haptic_loop.h    the fixed-rate loop with virtual coupling, on its own thread
//   job.h            the main job in one call: parts, device, fields, spectra, m', scripted session
//   search.h         where part 2 fits part 1 over all rotations (one FFT map each), shared among processes
//   live.h           a live session: the loop until stopped, driven from another thread (a mouse, a device)
//   bridge.h         the device bridge: its UDP datagrams, and the session's end of it
//   pose.h, error.h  rigid poses; the one exception type
//
// The papers the comments cite:
//   Behandish & Ilies 2016  M. Behandish, H. T. Ilies, "Haptic assembly using skeletal
//                           densities and Fourier transforms", 2016
//   Behandish & Ilies 2015  M. Behandish, H. T. Ilies, "Analytic methods for geometric
//                           modeling via spherical decomposition", CDL-TR-15-07, 2015
//   Faas 2010               D. Faas, "A hybrid method for haptic feedback to support manual
//                           virtual product assembly", PhD thesis, Iowa State University, 2010
// docs/*.md are installed with the headers' package under share/doc/snapfit.
#include "snapfit/assembly.h"
#include "snapfit/bridge.h"
#include "snapfit/error.h"
#include "snapfit/haptic_device.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/job.h"
#include "snapfit/live.h"
#include "snapfit/pose.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"
#include "snapfit/search.h"
#include "snapfit/tuning.h"
