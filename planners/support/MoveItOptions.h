#ifndef MESHGAP_PLANNERS_SUPPORT_MOVEIT_OPTIONS_H
#define MESHGAP_PLANNERS_SUPPORT_MOVEIT_OPTIONS_H

// The flags that pose a robot problem as MoveIt poses it, shared by meshgap_plan, meshgap_benchmark, meshgap_distance
// and meshgap_report: --urdf R.urdf [--srdf R.srdf] [--scene scene.yaml] [--request request.yaml], instead of --cfg
// (meshgap/robot/MoveItScene.h reads them). Header-only.

#include <boost/program_options.hpp>
#include <string>

#include "meshgap/Exception.h"
#include "meshgap/robot/MoveItScene.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief Declare --urdf, --srdf, --scene and --request in \e options, stored in \e files. */
        inline void addMoveItOptions(boost::program_options::options_description &options, MoveItFiles &files)
        {
            namespace po = boost::program_options;
            options.add_options()("urdf", po::value(&files.urdf),
                                  "with --scene and --request instead of --cfg: the robot (URDF)")(
                "srdf", po::value(&files.srdf), "with --urdf: its SRDF (disable_collisions pairs allowed)")(
                "scene", po::value(&files.scene),
                "with --urdf: a MoveIt planning scene (moveit_msgs/PlanningScene, YAML): obstacles, allowed "
                "collision matrix, robot state")("request", po::value(&files.request),
                                                 "with --urdf: a MoveIt motion plan request (YAML): start state, "
                                                 "goal joint constraints");
        }

        /** \brief True when any of --urdf, --srdf, --scene or --request is given. */
        inline bool moveItGiven(const MoveItFiles &files)
        {
            return !files.urdf.empty() || !files.srdf.empty() || !files.scene.empty() || !files.request.empty();
        }

        /** \brief True when the tool's problem is a robot problem: the MoveIt flags, or a robot .cfg. Throws
            meshgap::Exception for --cfg with the MoveIt flags, and for the MoveIt flags without --urdf. */
        inline bool isToolRobotProblem(const std::string &cfg, const MoveItFiles &files)
        {
            if (!moveItGiven(files))
                return !cfg.empty() && isRobotProblemFile(cfg);
            if (!cfg.empty())
                throw Exception("command line", "give either --cfg or --urdf with --scene and --request, not both");
            if (files.urdf.empty())
                throw Exception("command line", "--srdf, --scene and --request need --urdf (the robot)");
            return true;
        }

        /** \brief The robot problem of --cfg, or of the MoveIt flags (isToolRobotProblem() checked first). */
        inline RobotProblem readToolRobotProblem(const std::string &cfg, const MoveItFiles &files)
        {
            if (!isToolRobotProblem(cfg, files))
                throw Exception(cfg.empty() ? "command line" : cfg, "not a robot problem");
            return moveItGiven(files) ? readMoveItProblem(files) : readRobotProblem(cfg);
        }
    }  // namespace cli
}  // namespace meshgap

#endif
