#pragma once
// Numbers for the data block of snapfit's pages (report/html_page.h): large arrays as
// base64 of little-endian float32 (report/web/src/page_data.js decodes them), bit sets as
// base64 of bytes.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace snapfit {

// RFC 4648 base64 with padding.
std::string base64_encode(const unsigned char* data, std::size_t size);

// The values rounded to float32 (non-finite ones stay NaN or +-inf), as base64.
std::string float32_base64(const std::vector<double>& values);
std::string float32_base64(const std::vector<float>& values);

}  // namespace snapfit
