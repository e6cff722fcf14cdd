#include "sfm/run/run_page_options.h"

#include "io/core/error.h"

namespace comic::sfm {

void RunPageOptions::Check() const {
  COMIC_CHECK(max_points >= 1, kInvalidArgument, "report page: max_points must be >= 1");
  COMIC_CHECK(max_thumbnails >= 0, kInvalidArgument,
              "report page: max_thumbnails must be >= 0, got " << max_thumbnails);
  COMIC_CHECK(thumbnail_height >= 16 && thumbnail_height <= 512, kInvalidArgument,
              "report page: thumbnail_height must be in 16..512, got " << thumbnail_height);
  COMIC_CHECK(num_track_frames >= 0, kInvalidArgument,
              "report page: num_track_frames must be >= 0, got " << num_track_frames);
  COMIC_CHECK(track_frame_width >= 64 && track_frame_width <= 4096, kInvalidArgument,
              "report page: track_frame_width must be in 64..4096, got " << track_frame_width);
  COMIC_CHECK(jpeg_quality >= 1 && jpeg_quality <= 100, kInvalidArgument,
              "report page: jpeg_quality must be in 1..100, got " << jpeg_quality);
  COMIC_CHECK(max_matrix_cells >= 1 && max_matrix_cells <= 1000, kInvalidArgument,
              "report page: max_matrix_cells must be in 1..1000, got " << max_matrix_cells);
  html.Check();
}

}  // namespace comic::sfm
