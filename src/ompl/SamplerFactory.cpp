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
        ompl::base::ValidStateSamplerAllocator samplerOf()
        {
            return [](const ompl::base::SpaceInformation *si) { return std::make_shared<S>(si); };
        }

        const Registry<ompl::base::ValidStateSamplerAllocator> &samplerRegistry()
        {
            namespace ob = ompl::base;
            static const Registry<ob::ValidStateSamplerAllocator> samplers(
                "sampler", {
                               {"uniform", samplerOf<ob::UniformValidStateSampler>()},
                               {"gaussian", samplerOf<ob::GaussianValidStateSampler>()},
                               {"obstacle_based", samplerOf<ob::ObstacleBasedValidStateSampler>()},
                               {"bridge_test", samplerOf<ob::BridgeTestValidStateSampler>()},
                               {"max_clearance", samplerOf<ob::MaximizeClearanceValidStateSampler>()},
                               {"narrow_passage", samplerOf<NarrowPassageSampler>()},
                               {"retraction", samplerOf<RetractionSampler>()},
                               {"workspace_medial", samplerOf<WorkspaceMedialSampler>()},
                           });
            return samplers;
        }
    }  // namespace

    std::vector<std::string> validStateSamplerNames()
    {
        return samplerRegistry().names();
    }

    ompl::base::ValidStateSamplerAllocator validStateSamplerAllocator(const std::string &name, const std::string &where)
    {
        return samplerRegistry().at(name, where);
    }

    void setValidStateSampler(ompl::base::SpaceInformation &si, const std::string &name, const std::string &where)
    {
        si.setValidStateSamplerAllocator(validStateSamplerAllocator(name, where));
    }
}  // namespace meshgap
