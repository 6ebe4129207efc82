#ifndef MESHGAP_OMPL_MOTION_VALIDATOR_FACTORY_H
#define MESHGAP_OMPL_MOTION_VALIDATOR_FACTORY_H

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>

#include <string>
#include <vector>

#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/ompl/ClearanceField.h"
#include "meshgap/robot/RobotScene.h"

namespace meshgap
{
    /** \brief Motion validator names: discrete (OMPL's DiscreteMotionValidator, states sampled along the motion at
        the space's resolution) and clearance (certified: ClearanceMotionValidator for one rigid body,
        RobotMotionValidator for every kind of robot). */
    std::vector<std::string> motionValidatorNames();

    /** \brief Throws meshgap::Exception (prefixed \e where) naming \e name and the valid names when \e name is not
        one of motionValidatorNames(): the check of an option before the problem is loaded. */
    void checkMotionValidatorName(const std::string &name, const std::string &where = "motion");

    /** \brief The named motion validator for one rigid body whose validity checker is \e checker (clearance needs
        it in CERTIFIED mode). Throws meshgap::Exception (prefixed \e where: the option or file that named it)
        naming an unknown name and the valid ones, or a clearance validator on a FAST checker. */
    ompl::base::MotionValidatorPtr allocMotionValidator(const std::string &name,
                                                        const ompl::base::SpaceInformationPtr &si,
                                                        const ClearanceCheckerPtr &checker,
                                                        const std::string &where = "motion");

    /** \brief The named motion validator for a robot of many bodies in \e scene (a space made by
        robotStateSpace()). Throws meshgap::Exception (prefixed \e where) naming an unknown name and the valid ones. */
    ompl::base::MotionValidatorPtr allocMotionValidator(const std::string &name,
                                                        const ompl::base::SpaceInformationPtr &si,
                                                        const RobotSceneConstPtr &scene,
                                                        const std::string &where = "motion");

    /** \brief The certified motion validator of the robot \e field measures: ClearanceMotionValidator for a
        ClearanceChecker (CERTIFIED mode), RobotMotionValidator for a RobotChecker. Throws meshgap::Exception for
        a field that is neither, or not certified. */
    ompl::base::MotionValidatorPtr allocCertifiedMotionValidator(const ompl::base::SpaceInformationPtr &si,
                                                                 const ClearanceFieldPtr &field);
}  // namespace meshgap

#endif
