#include "frontend/matching/track.h"

#include <algorithm>
#include <set>
#include <utility>

#include "io/core/error.h"

namespace comic::frontend {

int Track::FeatureInFrame(int frame) const {
  const auto it =
      std::lower_bound(observations.begin(), observations.end(), frame,
                       [](const TrackObservation& obs, int f) { return obs.frame < f; });
  return it != observations.end() && it->frame == frame ? it->feature : -1;
}

void FeatureTracks::Check() const {
  COMIC_CHECK(
      frame_names.empty() || frame_names.size() == features.size(), kInvalidData,
      "tracks: " << frame_names.size() << " frame names for " << features.size() << " frames");
  COMIC_CHECK(
      descriptors.empty() || descriptors.size() == features.size(), kInvalidData,
      "tracks: descriptors for " << descriptors.size() << " of " << features.size() << " frames");
  for (size_t f = 0; f < descriptors.size(); ++f) {
    const cv::Mat& d = descriptors[f];
    COMIC_CHECK(d.rows == static_cast<int>(features[f].size()) &&
                    (d.rows == 0 || (d.type() == CV_8UC1 && d.cols == 128)),
                kInvalidData,
                "tracks: frame " << f
                                 << ": descriptors must be CV_8UC1, 128 columns, one row per "
                                    "feature ("
                                 << features[f].size() << "), got " << d.rows << "x" << d.cols);
  }
  std::set<std::pair<int, int>> used;
  for (size_t t = 0; t < tracks.size(); ++t) {
    int previous_frame = -1;
    for (const TrackObservation& obs : tracks[t].observations) {
      COMIC_CHECK(obs.frame >= 0 && obs.frame < static_cast<int>(features.size()), kInvalidData,
                  "track " << t << ": frame " << obs.frame << " out of range");
      COMIC_CHECK(
          obs.feature >= 0 && obs.feature < static_cast<int>(features[obs.frame].size()),
          kInvalidData,
          "track " << t << ": feature " << obs.feature << " out of range in frame " << obs.frame);
      COMIC_CHECK(obs.frame > previous_frame, kInvalidData,
                  "track " << t << ": frames not strictly increasing at frame " << obs.frame);
      COMIC_CHECK(used.insert({obs.frame, obs.feature}).second, kInvalidData,
                  "track " << t << ": feature " << obs.feature << " of frame " << obs.frame
                           << " already belongs to another track");
      previous_frame = obs.frame;
    }
  }
}

}  // namespace comic::frontend
