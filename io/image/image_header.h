// An image's size read from its header, before anything is decoded, so that the pixel budget
// (io/core/pixel_budget.h) refuses a small file declaring a huge image before the decoder
// allocates it (issue 29: an 875 kB PNG declaring 30000x30000 peaked at 937 MB in cv::imread
// before the old after-decode check refused it). OpenCV 4.6 has no header-only query
// (cv::ImageCollection came later), so the formats the sequences read are parsed here: PNG (IHDR),
// JPEG (the SOF segment), BMP (the DIB header), TIFF (tags 256/257 of the first IFD) and PNM
// (P1-P6). Other formats return no size and are checked after decoding, as before.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace comic::io {

struct ImageHeader {
  std::string format;  // "PNG", "JPEG", "BMP", "TIFF" or "PNM"
  int64_t width = 0;   // pixels, as declared
  int64_t height = 0;  // pixels, as declared
};

// The declared size of the image at `path`, recognised by its signature (not its extension).
// std::nullopt when the file cannot be read, has another format, or its header is cut short or
// malformed (the decoder then reports it). Reads a few bytes, never the pixel data. Throws
// comic::Error(kInvalidData) for a FIFO, socket or device, before opening it (io::CheckInputFile).
std::optional<ImageHeader> ReadImageHeader(const std::string& path);

// The same from bytes in memory (the start of a file).
std::optional<ImageHeader> ParseImageHeader(const std::string& bytes);

}  // namespace comic::io
