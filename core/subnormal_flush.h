#pragma once
// Subnormal floats flushed to zero in the calling thread while a SubnormalFlush lives
// (x86: MXCSR's flush-to-zero and denormals-are-zero bits; AArch64: FPCR.FZ), restored after.
//
// A part that settles at its fit approaches it exponentially, so its pose's offsets and
// rotation components fall below float's smallest normal (1.2e-38) once converted for the
// single-precision query and contact. Arithmetic on subnormals runs a slow microcode path
// on x86 (tens to hundreds of cycles an operation), which makes a frame several times
// slower while nothing moves; values that small are zero to every force the loop renders.
// Real-time audio and haptics set the same bits in their frame threads for this reason.
// A CPU OpenCL device may set its own bits around each kernel (PoCL does, from the program's
// build options): the query kernels are built with -cl-denorms-are-zero for that.

namespace snapfit {

class SubnormalFlush {
 public:
  SubnormalFlush();
  ~SubnormalFlush();
  SubnormalFlush(const SubnormalFlush&) = delete;
  SubnormalFlush& operator=(const SubnormalFlush&) = delete;

 private:
  unsigned long long previous_ = 0;
};

}  // namespace snapfit
