#ifndef MESHGAP_ROBOT_MULTI_BODY_ROBOT_H
#define MESHGAP_ROBOT_MULTI_BODY_ROBOT_H

#include <string>
#include <vector>

#include "meshgap/robot/RigidBodyRobot.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(MultiBodyRobot);

    /** \brief Several rigid bodies moving at once, each free in SE(2) or SE(3) (OMPL.app's multi-body problems): one
        frame and one link per body, the state the bodies' states one after the other (a compound OMPL state), and
        every body checked against every other. Each body's frame hangs from the world by rigidJoint(). */
    class MultiBodyRobot : public RobotModel
    {
    public:
        /** \brief One body of the robot. */
        struct Part
        {
            std::string name;
            BodyConstPtr body;
            RigidSpace space;
        };

        /** \brief Throws meshgap::Exception for no part, a null body or two parts of one name. */
        explicit MultiBodyRobot(const std::vector<Part> &parts);

        /** \brief Where part \e i's numbers start in a state. */
        std::size_t offset(std::size_t i) const { return offsets_[i]; }
        RigidSpace space(std::size_t i) const { return spaces_[i]; }

        /** \brief "N bodies in SE(2)" (or SE(3), or "SE(2) and SE(3)" when they differ). */
        std::string description() const override;

    private:
        std::vector<RigidSpace> spaces_;
        std::vector<std::size_t> offsets_;
    };
}  // namespace meshgap

#endif
