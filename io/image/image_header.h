// An image's size read from its header, before anything is decoded, so that the pixel budget
// (io/core/pixel_budget.h) refuses a small file declaring a huge image before the decoder
// allocates it. OpenCV 4.6 has no header-only query (cv::ImageCollection came later), and its
// decoders pick the format by content, not by the file's extension, so the header of every format
// it decodes is parsed here, recognised by its signature: PNG (IHDR), JPEG (the SOF segment), BMP
// (the DIB header), TIFF (tags 256/257 of the first IFD), PNM (P1-P6), PAM (P7), PFM (PF, Pf),
// WebP (the VP8, VP8L or VP8X chunk), Radiance HDR (the resolution line), Sun raster, JPEG 2000
// (a JP2 file's ihdr box or a codestream's SIZ segment) and OpenEXR (the dataWindow attribute).
// RequireImageHeader refuses anything else, so that nothing is decoded whose size is not known.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace comic::io {

struct ImageHeader {
  std::string format;  // "PNG", "JPEG", "BMP", "TIFF", "PNM", "PAM", "PFM", "WebP", ...
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

// The formats whose header is read, for messages: "PNG, JPEG, BMP, ..., OpenEXR".
const char* ReadableImageFormats();

// ReadImageHeader, or comic::Error(kInvalidData) naming `path` ("cannot decode image") when it
// gives none: such a file is not handed to the decoder at all, since its size could not be
// checked first. Throws as ReadImageHeader for a FIFO, socket or device, and kNotFound for a
// missing file.
ImageHeader RequireImageHeader(const std::string& path);

}  // namespace comic::io
