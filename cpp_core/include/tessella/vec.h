// Small value types shared by the whole core (Eigen fixed-size vectors).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross(): declared in Core, defined here

namespace tessella {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

}  // namespace tessella
