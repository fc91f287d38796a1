#pragma once
// Greyscale rasters as PNG (8-bit grey, zlib-deflated) and data: URIs, so that the report's page
// can show an occupancy grid pixel for cell and stay one self-contained file.

#include <cstdint>
#include <string>
#include <vector>

namespace scanloc {

// The PNG file of a width × height 8-bit grey image, `pixels` row-major from the top row.
// Throws std::invalid_argument when pixels.size() != width × height or either is 0.
std::string GreyscalePng(std::size_t width, std::size_t height,
                         const std::vector<std::uint8_t>& pixels);

// RFC 4648 base64, with padding.
std::string Base64(const std::string& bytes);

// "data:image/png;base64,…" of GreyscalePng(width, height, pixels).
std::string GreyscalePngDataUri(std::size_t width, std::size_t height,
                                const std::vector<std::uint8_t>& pixels);

}  // namespace scanloc
