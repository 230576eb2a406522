// Device self-check: each work-item evaluates a short polynomial and a transcendental,
// then each work-group reduces its results in local memory. The host compares with a
// double-precision reference, so a device that miscompiles arithmetic, local-memory
// reductions or barriers is caught before it computes forces.
// Options: -D REAL=float|double (double needs cl_khr_fp64), -D WG_SIZE=<work-group size>.
#ifndef REAL
#define REAL float
#endif
#ifndef WG_SIZE
#define WG_SIZE 64
#endif
#if defined(SNAPFIT_FP64)
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void device_check(__global const REAL* x,
                                                                                __global REAL* partial_sums,
                                                                                const int n) {
  __local REAL scratch[WG_SIZE];
  const int gid = get_global_id(0);
  const int lid = get_local_id(0);
  REAL value = (REAL)0;
  if (gid < n) {
    const REAL v = x[gid];
    value = ((REAL)2 * v - (REAL)3) * v + (REAL)1 + sin(v);  // (2v - 3)v + 1 + sin v
  }
  scratch[lid] = value;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int stride = WG_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride) scratch[lid] += scratch[lid + stride];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) partial_sums[get_group_id(0)] = scratch[0];
}
