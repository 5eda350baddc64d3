#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "render/camera.h"

namespace tracer {
namespace {

Camera task2_camera() {
    Camera camera;
    camera.eye = {0, 0, 7};
    camera.lookat = {0, 0, 0};
    camera.up = {0, 1, 0};
    camera.fovy_degrees = 45;
    camera.focal = 1;
    return camera;
}

TEST(Camera, ImageCenterLooksAtLookat) {
    PinholeCamera camera(task2_camera(), 1200, 800);
    Ray ray = camera.ray_through(600, 400);
    EXPECT_EQ(ray.origin, Vec3(0, 0, 7));
    EXPECT_NEAR(ray.direction.z, -1, 1e-15);
}

TEST(Camera, FieldOfViewIsVerticalAndInDegrees) {
    PinholeCamera camera(task2_camera(), 1200, 800);
    Ray top = camera.ray_through(600, 0);  // top edge, middle column
    double half_angle = std::atan2(top.direction.y, -top.direction.z);
    EXPECT_NEAR(half_angle, 22.5 * M_PI / 180, 1e-12);
}

TEST(Camera, RowZeroIsTheTopAndColumnZeroTheLeft) {
    PinholeCamera camera(task2_camera(), 1200, 800);
    Ray top_left = camera.ray_through(0.5, 0.5);
    EXPECT_GT(top_left.direction.y, 0);
    EXPECT_LT(top_left.direction.x, 0);
}

TEST(Camera, FocalDistanceDoesNotChangeTheRays) {
    Camera far = task2_camera();
    far.focal = 10;
    Ray a = PinholeCamera(task2_camera(), 640, 480).ray_through(17.5, 300.5);
    Ray b = PinholeCamera(far, 640, 480).ray_through(17.5, 300.5);
    EXPECT_NEAR(glm::length(a.direction - b.direction), 0, 1e-15);
}

}  // namespace
}  // namespace tracer
