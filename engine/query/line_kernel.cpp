#include "engine/query/line_kernel.h"

#include <algorithm>

namespace snapfit {

void upload_line_selection(QueryLaunch& launch, const LineSelection& selection, int table_half, cl::Buffer& records,
                           std::size_t& capacity) {
  cl::Kernel& k = launch.kernel();
  const std::size_t n = std::max<std::size_t>(selection.lines.size(), 1);
  if (n > capacity) {
    capacity = std::max(n + n / 4, std::size_t(64));
    records = cl::Buffer(launch.context(), CL_MEM_READ_ONLY, sizeof(LineRecord) * capacity);
    k.setArg(kLineRecords, records);
  }
  if (!selection.lines.empty())
    launch.queue().enqueueWriteBuffer(records, CL_TRUE, 0, sizeof(LineRecord) * selection.lines.size(),
                                      selection.lines.data());
  k.setArg(kLineExtraCount, static_cast<cl_int>(selection.extras.size()));
  k.setArg(kLineFolded, static_cast<cl_int>(selection.folded ? 1 : 0));
  k.setArg(kLineCount, static_cast<cl_int>(selection.lines.size()));
  k.setArg(kLineTableHalf, static_cast<cl_int>(table_half));
}

}  // namespace snapfit
