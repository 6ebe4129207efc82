#ifndef MESHGAP_DISTANCE_DISTANCE_SOLVER_H
#define MESHGAP_DISTANCE_DISTANCE_SOLVER_H

#include <ompl/base/GenericParam.h>
#include <stdexcept>
#include <string>

#include "meshgap/ClassForward.h"
#include "meshgap/Exception.h"
#include "meshgap/distance/DistanceQuery.h"
#include "meshgap/geometry/Body.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(DistanceSolver);

    /** \brief One algorithm for the minimum node-to-node distance between two bodies. Parameters are set through
        params() (OMPL's ParamSet, so a command line or a .cfg can reach them by name) before queries run; solve()
        is const and thread-safe: all per-query state lives in the call. */
    class DistanceSolver
    {
    public:
        explicit DistanceSolver(std::string name) : name_(std::move(name)) {}
        virtual ~DistanceSolver() = default;

        const std::string &getName() const { return name_; }

        /** \brief Minimum distance between the nodes of \e a and of \e b, where \e X_AB is B's pose in A's frame. */
        virtual void solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                           DistanceResult &result) const = 0;

        ompl::base::ParamSet &params() { return params_; }
        const ompl::base::ParamSet &params() const { return params_; }

    protected:
        /** \brief Throws meshgap::Exception (naming the solver) for a body without nodes or a start pair out of
            range. */
        void checkRequest(const Body &a, const Body &b, const DistanceRequest &request) const;

        /** \brief Run \e set, a setter whose meshgap::Exception says a value is out of range, for a ParamSet setter:
            the exception becomes the std::invalid_argument that ParamSet::setParam() reports as false. So each
            parameter has one range check, the setter's. */
        template <typename Set>
        static void setChecked(Set &&set)
        {
            try
            {
                set();
            }
            catch (const Exception &e)
            {
                throw std::invalid_argument(e.what());
            }
        }

        std::string name_;
        ompl::base::ParamSet params_;
    };
}  // namespace meshgap

#endif
