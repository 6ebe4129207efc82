#include "meshgap/ompl/SamplerFactory.h"

#include <ompl/base/samplers/BridgeTestValidStateSampler.h>
#include <ompl/base/samplers/GaussianValidStateSampler.h>
#include <ompl/base/samplers/MaximizeClearanceValidStateSampler.h>
#include <ompl/base/samplers/ObstacleBasedValidStateSampler.h>
#include <ompl/base/samplers/UniformValidStateSampler.h>

#include "meshgap/Registry.h"
#include "meshgap/ompl/NarrowPassageSampler.h"
#include "meshgap/ompl/RetractionSampler.h"
#include "meshgap/ompl/WorkspaceMedialSampler.h"

namespace meshgap
{
    namespace
    {
        template <typename S>
        ompl::base::ValidStateSamplerAllocator make()
        {
            return [](const ompl::base::SpaceInformation *si) { return std::make_shared<S>(si); };
        }

        const Registry<ompl::base::ValidStateSamplerAllocator> &registry()
        {
            namespace ob = ompl::base;
            static const Registry<ob::ValidStateSamplerAllocator> samplers(
                "sampler", {
                               {"uniform", make<ob::UniformValidStateSampler>()},
                               {"gaussian", make<ob::GaussianValidStateSampler>()},
                               {"obstacle_based", make<ob::ObstacleBasedValidStateSampler>()},
                               {"bridge_test", make<ob::BridgeTestValidStateSampler>()},
                               {"max_clearance", make<ob::MaximizeClearanceValidStateSampler>()},
                               {"narrow_passage", make<NarrowPassageSampler>()},
                               {"retraction", make<RetractionSampler>()},
                               {"workspace_medial", make<WorkspaceMedialSampler>()},
                           });
            return samplers;
        }
    }  // namespace

    std::vector<std::string> validStateSamplerNames()
    {
        return registry().names();
    }

    ompl::base::ValidStateSamplerAllocator validStateSamplerAllocator(const std::string &name, const std::string &where)
    {
        return registry().at(name, where);
    }

    void setValidStateSampler(ompl::base::SpaceInformation &si, const std::string &name, const std::string &where)
    {
        si.setValidStateSamplerAllocator(validStateSamplerAllocator(name, where));
    }
}  // namespace meshgap
