// Two unit triangles one unit apart: the node distance is 1.
#include <cstdio>
#include <meshgap/distance/SolverFactory.h>

int main()
{
    meshgap::Mesh m;
    m.source = "consumer";
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}};
    meshgap::BodyOptions options;
    options.gridSize = 0;
    const auto body = meshgap::Body::build(m, options);
    Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
    X_AB.translation().z() = 1.0;
    meshgap::DistanceResult result;
    meshgap::allocSolver("enumeration")->solve(*body, *body, X_AB, meshgap::DistanceRequest(), result);
    std::printf("distance %g\n", result.distance);
    return result.distance == 1.0 ? 0 : 1;
}
