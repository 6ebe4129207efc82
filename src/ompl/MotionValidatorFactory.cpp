#include "meshgap/ompl/MotionValidatorFactory.h"

#include <ompl/base/DiscreteMotionValidator.h>

#include <functional>

#include "meshgap/Exception.h"
#include "meshgap/Registry.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/RobotMotionValidator.h"

namespace meshgap
{
    namespace
    {
        /** \brief What a validator is made for: one rigid body (checker) or a robot (scene); discrete needs
            neither. */
        struct Target
        {
            ompl::base::SpaceInformationPtr si;
            ClearanceCheckerPtr checker;
            RobotSceneConstPtr scene;
            std::string where;
        };

        using Make = std::function<ompl::base::MotionValidatorPtr(const Target &)>;

        ompl::base::MotionValidatorPtr clearanceValidator(const Target &t)
        {
            if (t.checker)
            {
                if (t.checker->mode() != ClearanceChecker::Mode::CERTIFIED)
                    throw Exception(t.where, "the clearance motion validator needs the certified checker (exact "
                                             "clearance), not the fast one");
                return std::make_shared<ClearanceMotionValidator>(t.si, t.checker);
            }
            if (!t.scene)
                throw Exception(t.where, "the clearance motion validator needs a validity checker or robot scene");
            return std::make_shared<RobotMotionValidator>(t.si, t.scene, t.scene->robot());
        }

        const Registry<Make> &validatorRegistry()
        {
            static const Registry<Make> validators(
                "motion validator",
                {
                    {"discrete",
                     [](const Target &t) { return std::make_shared<ompl::base::DiscreteMotionValidator>(t.si); }},
                    {"clearance", clearanceValidator},
                });
            return validators;
        }
    }  // namespace

    std::vector<std::string> motionValidatorNames()
    {
        return validatorRegistry().names();
    }

    void checkMotionValidatorName(const std::string &name, const std::string &where)
    {
        validatorRegistry().at(name, where);
    }

    ompl::base::MotionValidatorPtr allocMotionValidator(const std::string &name,
                                                        const ompl::base::SpaceInformationPtr &si,
                                                        const ClearanceCheckerPtr &checker, const std::string &where)
    {
        return validatorRegistry().at(name, where)(Target{si, checker, nullptr, where});
    }

    ompl::base::MotionValidatorPtr allocMotionValidator(const std::string &name,
                                                        const ompl::base::SpaceInformationPtr &si,
                                                        const RobotSceneConstPtr &scene, const std::string &where)
    {
        return validatorRegistry().at(name, where)(Target{si, nullptr, scene, where});
    }

    ompl::base::MotionValidatorPtr allocCertifiedMotionValidator(const ompl::base::SpaceInformationPtr &si,
                                                                 const ClearanceFieldPtr &field)
    {
        if (auto checker = std::dynamic_pointer_cast<ClearanceChecker>(field))
            return allocMotionValidator("clearance", si, checker, "certified motion validator");
        if (auto robot = std::dynamic_pointer_cast<RobotChecker>(field))
            return allocMotionValidator("clearance", si, robot->scenePtr(), "certified motion validator");
        throw Exception("certified motion validator", "the clearance field is neither a ClearanceChecker nor a "
                                                      "RobotChecker");
    }
}  // namespace meshgap
