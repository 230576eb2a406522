#pragma once
// snapfit: haptic guidance for assembling rigid parts (Behandish & Ilies 2016's skeletal densities and
// truncated Fourier sums) on any OpenCL device. The whole public API:
//   scene.h          scenes: parts, poses, descriptor, grid and haptics parameters, load_scene
//   assembly.h       a scene's parts on a device with fields and spectra precomputed (cached)
//   query.h          energy, force and torque of part 2 at a pose, per frame, truncated to m' modes
//   tuning.h         m' for the scene's frame budget on this device (auto_tune)
//   accuracy.h       what the frame budget buys: each strategy's m', frame time and error
//   devices.h        the OpenCL devices, the default choice and the self-check
//   inspect.h        a part file's mesh report, a scene's parts and compute plan (no device)
//   fields.h         a scene part's descriptor fields on its grid
//   maps.h           the energy for every translation at one rotation
//   collision.h      the collision verdict on the truncated sum (indicator scenes)
//   spheres.h        a part's spherical decomposition and its error
//   grid.h, export.h sample grids; .vti and .vtp files for ParaView, STL and OBJ, any text file
//   mesh.h           triangle meshes, their refinement and their cut by an axis plane
//   slice_image.h    a grid field's slice as a colour-mapped PNG
//   progress.h       progress bars on stderr
//   haptic_device.h  what a haptic device implements (read pose, send wrench, limits)
//   haptic_loop.h    the fixed-rate loop with virtual coupling, on its own thread
//   job.h            the main job in one call: parts, device, fields, spectra, m', scripted session
//   job_facts.h      what a job built and measured, as plain data (its report is drawn from it)
//   search.h         where part 2 fits part 1 over all rotations (one FFT map each), shared among processes
//   live.h           a live session: the loop until stopped, driven from another thread (a mouse, a device)
//   bridge.h         the device bridge: its UDP datagrams, and the session's end of it
//   pose.h, error.h  rigid poses and their errors; the one exception type
//   pose_json.h      a pose in the scene files' JSON shape
//   quantile.h       order statistics of timing samples
//
// The papers the comments cite:
//   Behandish & Ilies 2016  M. Behandish, H. T. Ilies, "Haptic assembly using skeletal
//                           densities and Fourier transforms", 2016
//   Behandish & Ilies 2015  M. Behandish, H. T. Ilies, "Analytic methods for geometric
//                           modeling via spherical decomposition", CDL-TR-15-07, 2015
//   Faas 2010               D. Faas, "A hybrid method for haptic feedback to support manual
//                           virtual product assembly", PhD thesis, Iowa State University, 2010
// docs/*.md are installed with the headers' package under share/doc/snapfit.
#include "snapfit/accuracy.h"
#include "snapfit/assembly.h"
#include "snapfit/bridge.h"
#include "snapfit/collision.h"
#include "snapfit/devices.h"
#include "snapfit/error.h"
#include "snapfit/export.h"
#include "snapfit/fields.h"
#include "snapfit/grid.h"
#include "snapfit/haptic_device.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/inspect.h"
#include "snapfit/job.h"
#include "snapfit/job_facts.h"
#include "snapfit/live.h"
#include "snapfit/maps.h"
#include "snapfit/mesh.h"
#include "snapfit/pose.h"
#include "snapfit/pose_json.h"
#include "snapfit/progress.h"
#include "snapfit/quantile.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"
#include "snapfit/search.h"
#include "snapfit/slice_image.h"
#include "snapfit/spheres.h"
#include "snapfit/tuning.h"
