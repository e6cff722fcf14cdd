// Moving objects (render/object_motion.h): a point of the object is where its velocity and yaw
// rate put it at any time, turning about the pivot; values that are not finite or that no
// sub-frame could follow are refused.
#include "render/object_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "io/core/error.h"

namespace comic::render {
namespace {

TEST(ObjectMotion, APointMovesByTheVelocityTimesTheTime) {
  ObjectMotion motion;
  EXPECT_FALSE(motion.Moves());
  motion.velocity = Eigen::Vector3d(0.5, 0.0, -0.2);
  EXPECT_TRUE(motion.Moves());
  const Eigen::Vector3d point(3.0, 1.0, 7.0);
  EXPECT_EQ(motion.PointAt(point, 0.0), point);
  for (double time : {1.0, 4.0, 2.5, -3.0}) {
    EXPECT_LT((motion.PointAt(point, time) - (point + time * motion.velocity)).norm(), 1e-12)
        << time;
  }
  // Directions are not moved by a translation.
  EXPECT_EQ(motion.DirectionAt(Eigen::Vector3d::UnitZ(), 5.0), Eigen::Vector3d::UnitZ());
}

TEST(ObjectMotion, ItTurnsAboutTheVerticalThroughItsPivot) {
  ObjectMotion motion;
  motion.yaw_rate = M_PI / 20;  // a quarter turn in 10 frames
  motion.pivot = Eigen::Vector3d(2.0, 0.0, 5.0);
  EXPECT_TRUE(motion.Moves());
  // z turns towards x; heights stay; the pivot stays.
  EXPECT_LT((motion.DirectionAt(Eigen::Vector3d::UnitZ(), 10.0) - Eigen::Vector3d::UnitX()).norm(),
            1e-12);
  EXPECT_LT((motion.PointAt(Eigen::Vector3d(2.0, 3.0, 6.0), 10.0) - Eigen::Vector3d(3.0, 3.0, 5.0))
                .norm(),
            1e-12);
  EXPECT_LT((motion.PointAt(motion.pivot, 7.0) - motion.pivot).norm(), 1e-12);
  // With a velocity too, the turned point is carried along.
  motion.velocity = Eigen::Vector3d(0.0, 0.0, 1.0);
  EXPECT_LT((motion.PointAt(Eigen::Vector3d(2.0, 3.0, 6.0), 10.0) - Eigen::Vector3d(3.0, 3.0, 15.0))
                .norm(),
            1e-12);
}

TEST(ObjectMotion, ValuesNotFiniteOrTooFastAreRefused) {
  ObjectMotion motion;
  motion.velocity = Eigen::Vector3d(1.0, 0.0, 2.0);
  motion.yaw_rate = 0.1;
  motion.Check();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto refused = [](const ObjectMotion& m) {
    try {
      m.Check();
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
      return true;
    }
    return false;
  };
  ObjectMotion bad = motion;
  bad.velocity.x() = nan;
  EXPECT_TRUE(refused(bad));
  bad = motion;
  bad.velocity.z() = 1e9;
  EXPECT_TRUE(refused(bad));
  bad = motion;
  bad.yaw_rate = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(refused(bad));
  bad = motion;
  bad.yaw_rate = -4.0;  // more than half a turn per frame
  EXPECT_TRUE(refused(bad));
  bad = motion;
  bad.pivot.y() = nan;
  EXPECT_TRUE(refused(bad));
}

}  // namespace
}  // namespace comic::render
