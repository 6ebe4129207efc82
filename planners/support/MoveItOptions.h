#ifndef MESHGAP_PLANNERS_SUPPORT_MOVEIT_OPTIONS_H
#define MESHGAP_PLANNERS_SUPPORT_MOVEIT_OPTIONS_H

// The flags that pose a robot problem as MoveIt poses it, shared by meshgap_plan, meshgap_benchmark, meshgap_distance
// and meshgap_report: --urdf R.urdf [--srdf R.srdf] [--scene scene.yaml] [--request request.yaml], instead of --cfg
// (meshgap/robot/MoveItScene.h reads them). Header-only.

#include <boost/program_options.hpp>
#include <string>

#include "meshgap/Exception.h"
#include "meshgap/robot/MoveItScene.h"
#include "meshgap/robot/RobotProblem.h"

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

        /** \brief The tool's problem, whatever its kind: --cfg as readProblem() reads it (the library tells the kinds
            apart), or the MoveIt flags' robot problem. Throws meshgap::Exception for --cfg with the MoveIt flags, for
            the MoveIt flags without --urdf, for neither, and as the readers do. */
        inline Problem readToolProblem(const std::string &cfg, const MoveItFiles &files)
        {
            if (!moveItGiven(files))
            {
                if (cfg.empty())
                    throw Exception("command line", "--cfg FILE (or --urdf with --scene and --request) is required; "
                                                    "see --help");
                return readProblem(cfg);
            }
            if (!cfg.empty())
                throw Exception("command line", "give either --cfg or --urdf with --scene and --request, not both");
            if (files.urdf.empty())
                throw Exception("command line", "--srdf, --scene and --request need --urdf (the robot)");
            Problem problem;
            problem.robot = readMoveItProblem(files);
            return problem;
        }

        /** \brief The tool's problem as a robot problem, whatever its kind (readToolProblem(); a single body through
            rigidBodyProblem(), a robot of one link). Throws as readToolProblem() and the mesh loader do. */
        inline RobotProblem readToolRobotProblem(const std::string &cfg, const MoveItFiles &files)
        {
            Problem problem = readToolProblem(cfg, files);
            return problem.robot ? std::move(*problem.robot) : rigidBodyProblem(*problem.rigidBody);
        }
    }  // namespace cli
}  // namespace meshgap

#endif
