#include "core/subnormal_flush.h"

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace snapfit {
namespace {

#if defined(__x86_64__) || defined(__i386__)
constexpr unsigned flush_to_zero = 0x8000;       // MXCSR.FTZ: subnormal results become 0
constexpr unsigned denormals_are_zero = 0x0040;  // MXCSR.DAZ: subnormal inputs read as 0
#elif defined(__aarch64__)
constexpr unsigned long long fpcr_fz = 1ull << 24;  // FPCR.FZ: both, for single and double
#endif

}  // namespace

SubnormalFlush::SubnormalFlush() {
#if defined(__x86_64__) || defined(__i386__)
  previous_ = _mm_getcsr();
  _mm_setcsr(static_cast<unsigned>(previous_) | flush_to_zero | denormals_are_zero);
#elif defined(__aarch64__)
  unsigned long long fpcr = 0;
  __asm__ volatile("mrs %0, fpcr" : "=r"(fpcr));
  previous_ = fpcr;
  fpcr |= fpcr_fz;
  __asm__ volatile("msr fpcr, %0" : : "r"(fpcr));
#endif
}

SubnormalFlush::~SubnormalFlush() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_setcsr(static_cast<unsigned>(previous_));
#elif defined(__aarch64__)
  __asm__ volatile("msr fpcr, %0" : : "r"(previous_));
#endif
}

}  // namespace snapfit
