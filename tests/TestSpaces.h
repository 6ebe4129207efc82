#ifndef MESHGAP_TESTS_TEST_SPACES_H
#define MESHGAP_TESTS_TEST_SPACES_H

#include <ompl/base/spaces/SE3StateSpace.h>

#include <memory>

namespace meshgap::test
{
    /** \brief An SE(3) state space whose translation is bounded by the cube [-extent, extent]^3. */
    inline std::shared_ptr<ompl::base::SE3StateSpace> se3Space(double extent)
    {
        auto space = std::make_shared<ompl::base::SE3StateSpace>();
        ompl::base::RealVectorBounds bounds(3);
        bounds.setLow(-extent);
        bounds.setHigh(extent);
        space->setBounds(bounds);
        return space;
    }
}  // namespace meshgap::test

#endif
