#include "cli/cli_terms.h"

#include <utility>

namespace snapfit::cli {

namespace {

// Request members (include/snapfit/job.h, search.h, inspect.h) and the options that set them.
const std::pair<const char*, const char*> kOptions[] = {
    {"JobRequest::device", "--device"},          {"JobRequest::modes", "--modes"},
    {"JobRequest::strategy", "--strategy"},      {"SearchRequest::map_fft", "--map-fft"},
    {"SearchRequest::map_batch", "--map-batch"}, {"MeshFileRequest::solid", "mesh-info's --solid"},
};

}  // namespace

std::string in_cli_terms(std::string text) {
  for (const auto& [member, option] : kOptions) {
    const std::string from = member, to = option;
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
      text.replace(at, from.size(), to);
  }
  return text;
}

}  // namespace snapfit::cli
