#ifndef MESHGAP_TESTS_TEST_SOLIDS_H
#define MESHGAP_TESTS_TEST_SOLIDS_H

// One solid of each primitive kind, of sizes about a mesh's: the shapes the primitive tests and the primitive bench
// compare with FCL's.

#include <vector>

#include "meshgap/geometry/Primitive.h"

namespace meshgap::test
{
    /** \brief A box, a sphere, a cylinder, a capsule and a cone, each at its body's origin (pose the identity). */
    inline std::vector<Primitive> oneSolidOfEachKind()
    {
        std::vector<Primitive> all(5);
        all[0].kind = Primitive::Kind::BOX, all[0].size = Eigen::Vector3d(0.3, 0.5, 0.8);
        all[1].kind = Primitive::Kind::SPHERE, all[1].size = Eigen::Vector3d(0.35, 0, 0);
        all[2].kind = Primitive::Kind::CYLINDER, all[2].size = Eigen::Vector3d(0.25, 0.9, 0);
        all[3].kind = Primitive::Kind::CAPSULE, all[3].size = Eigen::Vector3d(0.2, 0.7, 0);
        all[4].kind = Primitive::Kind::CONE, all[4].size = Eigen::Vector3d(0.3, 0.8, 0);
        return all;
    }
}  // namespace meshgap::test

#endif
