// Fuzz target: the JPEG EXIF focal reader (io/image/exif_focal.h). The bytes are read as a JPEG,
// and as the TIFF block of an Exif segment spliced into a minimal JPEG, so that mutations reach
// the IFD walk directly. Bad EXIF is "no EXIF": nothing may crash or read out of bounds, and a
// focal the reader does give must be finite and positive at every image size tried.
#include <cmath>
#include <string>

#include "io/image/exif_focal.h"

namespace {

void CheckFocals(const std::optional<comic::io::ExifFocal>& exif) {
  if (!exif) return;
  for (const auto& [width, height] : {std::pair{64, 48}, std::pair{4000, 3000}, std::pair{1, 1}}) {
    const auto focal = comic::io::ExifFocalInPixels(*exif, width, height);
    if (focal && !(std::isfinite(focal->focal_px) && focal->focal_px > 0)) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  CheckFocals(comic::io::ParseJpegExifFocal(bytes));
  if (size <= 0xFFFF - 8) {
    const size_t length = 2 + 6 + size;
    std::string jpeg = "\xFF\xD8\xFF\xE1";
    jpeg += static_cast<char>(length >> 8);
    jpeg += static_cast<char>(length & 0xFF);
    jpeg += std::string("Exif\0\0", 6) + bytes + "\xFF\xD9";
    CheckFocals(comic::io::ParseJpegExifFocal(jpeg));
  }
  return 0;
}
