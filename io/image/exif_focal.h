// The focal length a photo's EXIF states, read from a JPEG's APP1 "Exif" segment without a
// library: the TIFF header (either byte order), IFD0, its ExifIFD pointer (tag 0x8769), and there
// FocalLength (0x920A), FocalLengthIn35mmFilm (0xA405), FocalPlaneXResolution (0xA20E),
// FocalPlaneResolutionUnit (0xA210) and PixelX/YDimension (0xA002/0xA003). Every read is bounded
// by the segment, only one IFD pointer is followed (so offsets that point back cannot loop), and
// anything cut short or malformed reads as "no EXIF".
//
//   std::optional<ExifFocal> exif = ReadJpegExifFocal("photo.jpg");
//   std::optional<ExifFocalPixels> f = exif ? ExifFocalInPixels(*exif, 4000, 3000) : std::nullopt;
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace comic::io {

// The tags that give the focal length, each absent when the file lacks it or states 0 (EXIF's
// "unknown").
struct ExifFocal {
  std::optional<double> focal_length_mm;           // FocalLength
  std::optional<double> focal_length_35mm;         // FocalLengthIn35mmFilm
  std::optional<double> focal_plane_x_resolution;  // FocalPlaneXResolution: pixels per unit
  int focal_plane_resolution_unit = 2;             // 2 inch (EXIF's default), 3 cm, 4 mm, 5 µm
  std::optional<int64_t> pixel_x_dimension;        // PixelXDimension: the image width EXIF saw
  std::optional<int64_t> pixel_y_dimension;        // PixelYDimension

  // True when any tag that gives a focal length is present.
  bool HasFocal() const { return focal_length_mm || focal_length_35mm; }
};

// The EXIF tags of a JPEG file's bytes (from its start). std::nullopt when the bytes are not a
// JPEG, have no Exif APP1 segment before the scan, or it is malformed.
std::optional<ExifFocal> ParseJpegExifFocal(std::string_view bytes);

// The same for the file at `path`, reading at most its first 256 kB. std::nullopt also when the
// file cannot be read; never throws.
std::optional<ExifFocal> ReadJpegExifFocal(const std::string& path);

struct ExifFocalPixels {
  double focal_px = 0;  // at the image size given
  std::string from;     // which tags, e.g. "FocalLengthIn35mmFilm 28 mm"
};

// The focal length in pixels of a `width` x `height` image, as COLMAP's Bitmap::ExifFocalLength
// computes it: f35 / 35 · max(w, h) from FocalLengthIn35mmFilm; else FocalLength / sensor width ·
// max(w, h), the sensor width being PixelXDimension (or `width`) / FocalPlaneXResolution;
// otherwise std::nullopt.
std::optional<ExifFocalPixels> ExifFocalInPixels(const ExifFocal& exif, int width, int height);

}  // namespace comic::io
