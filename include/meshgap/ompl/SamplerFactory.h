#ifndef MESHGAP_OMPL_SAMPLER_FACTORY_H
#define MESHGAP_OMPL_SAMPLER_FACTORY_H

#include <ompl/base/SpaceInformation.h>

#include <string>
#include <vector>

namespace meshgap
{
    /** \brief Valid-state sampler names, as OMPL.app's cfg key [problem] sampler= spells OMPL's (uniform, gaussian,
        obstacle_based, bridge_test, max_clearance) and meshgap's narrow_passage (NarrowPassageSampler), retraction
        (RetractionSampler) and workspace_medial (WorkspaceMedialSampler). */
    std::vector<std::string> validStateSamplerNames();

    /** \brief The allocator of the named valid-state sampler. Throws meshgap::Exception (prefixed \e where: the
        option or file that named it) listing the valid names for an unknown one. */
    ompl::base::ValidStateSamplerAllocator validStateSamplerAllocator(const std::string &name,
                                                                      const std::string &where = "sampler");

    /** \brief Make the named sampler the one \e si allocates for planners (setValidStateSamplerAllocator()). */
    void setValidStateSampler(ompl::base::SpaceInformation &si, const std::string &name,
                              const std::string &where = "sampler");
}  // namespace meshgap

#endif
