#include "meshgap/ompl/SamplerFactory.h"

#include <ompl/base/samplers/BridgeTestValidStateSampler.h>
#include <ompl/base/samplers/GaussianValidStateSampler.h>
#include <ompl/base/samplers/MaximizeClearanceValidStateSampler.h>
#include <ompl/base/samplers/ObstacleBasedValidStateSampler.h>
#include <ompl/base/samplers/UniformValidStateSampler.h>

#include "meshgap/Exception.h"
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

        const std::vector<std::pair<std::string, ompl::base::ValidStateSamplerAllocator>> &registry()
        {
            namespace ob = ompl::base;
            static const std::vector<std::pair<std::string, ob::ValidStateSamplerAllocator>> samplers = {
                {"uniform", make<ob::UniformValidStateSampler>()},
                {"gaussian", make<ob::GaussianValidStateSampler>()},
                {"obstacle_based", make<ob::ObstacleBasedValidStateSampler>()},
                {"bridge_test", make<ob::BridgeTestValidStateSampler>()},
                {"max_clearance", make<ob::MaximizeClearanceValidStateSampler>()},
                {"narrow_passage", make<NarrowPassageSampler>()},
                {"retraction", make<RetractionSampler>()},
                {"workspace_medial", make<WorkspaceMedialSampler>()},
            };
            return samplers;
        }
    }  // namespace

    std::vector<std::string> validStateSamplerNames()
    {
        std::vector<std::string> names;
        for (const auto &entry : registry())
            names.push_back(entry.first);
        return names;
    }

    ompl::base::ValidStateSamplerAllocator validStateSamplerAllocator(const std::string &name, const std::string &where)
    {
        for (const auto &entry : registry())
            if (entry.first == name)
                return entry.second;
        std::string valid;
        for (const std::string &n : validStateSamplerNames())
            valid += (valid.empty() ? "" : ", ") + n;
        throw Exception(where, "unknown sampler '" + name + "'; valid names: " + valid);
    }

    void setValidStateSampler(ompl::base::SpaceInformation &si, const std::string &name, const std::string &where)
    {
        si.setValidStateSamplerAllocator(validStateSamplerAllocator(name, where));
    }
}  // namespace meshgap
