#include "meshgap/robot/Joint.h"

#include <cmath>

#include "meshgap/Exception.h"

namespace meshgap
{
    // The build writes one MESHGAP_JOINT(Name) line per file src/robot/joints/Name.cpp into JointTypes.inc.
#define MESHGAP_JOINT(Name) const JointType &Name##Type();
#include "meshgap/robot/JointTypes.inc"
#undef MESHGAP_JOINT

    const std::vector<const JointType *> &jointTypes()
    {
#define MESHGAP_JOINT(Name) &Name##Type(),
        static const std::vector<const JointType *> types{
#include "meshgap/robot/JointTypes.inc"
        };
#undef MESHGAP_JOINT
        return types;
    }

    std::string jointTypeNames()
    {
        std::string names;
        for (const JointType *t : jointTypes())
            names += (names.empty() ? "" : ", ") + std::string(t->name);
        return names;
    }

    JointConstPtr makeJoint(const std::string &type, const JointSpec &spec)
    {
        for (const JointType *t : jointTypes())
            if (type == t->name)
                return t->make(spec);
        throw Exception("joint", "an unknown type '" + type + "' (" + jointTypeNames() + ")");
    }

    Eigen::Vector3d unitAxis(const JointSpec &spec)
    {
        if (!(spec.axis.cwiseAbs().maxCoeff() > 0.0 && spec.axis.allFinite()))
            throw Exception("its axis", "zero or not finite");
        return spec.axis.stableNormalized();
    }

    double Joint::neutral(std::size_t k) const
    {
        const double lo = lower(k), hi = upper(k);
        return 0.0 >= lo && 0.0 <= hi ? 0.0 : 0.5 * (lo + hi);
    }
}  // namespace meshgap
