// What report.html (sfm/run/run_page.h) holds beyond the numbers: how many points the 3-D view
// keeps, how many frames are shown and how large, and where three.js is read from. The defaults
// keep the page of a 10 000-frame run under 20 MB (docs/report_page.md).
#pragma once

#include <cstddef>

#include "io/report/html_page.h"

namespace comic::sfm {

struct RunPageOptions {
  size_t max_points = 200000;   // 3-D points in the view; more are subsampled (the page says so)
  int max_thumbnails = 40;      // frames in the thumbnail strip, spread evenly over the clip
  int thumbnail_height = 72;    // pixels
  int num_track_frames = 4;     // frames drawn with their features and tracks
  int track_frame_width = 900;  // pixels: larger frames are shrunk to it
  int jpeg_quality = 80;        // of the pictures in the page (1..100)
  // Cells a side of the matrix of tracks shared between frames: more frames are grouped.
  int max_matrix_cells = 200;
  io::HtmlPageOptions html;  // where three.js is read from
  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

}  // namespace comic::sfm
