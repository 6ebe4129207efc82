#include "support/PathFile.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/InputFile.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/scene/Pose.h"

namespace meshgap
{
    ompl::geometric::PathGeometric readPathFile(const std::string &file, const ompl::base::SpaceInformationPtr &si)
    {
        namespace ob = ompl::base;
        checkInputFile(file);
        std::ifstream in(file);
        if (!in)
            throw Exception(file, "cannot open the path file");
        const ob::StateSpace &space = *si->getStateSpace();
        const bool planar = space.getType() == ob::STATE_SPACE_SE2;
        ompl::geometric::PathGeometric path(si);
        ob::State *state = si->allocState();
        std::string line;
        try
        {
            for (std::size_t number = 1; std::getline(in, line); ++number)
            {
                const auto first = line.find_first_not_of(" \t\r");
                if (first == std::string::npos || line[first] == '#')
                    continue;
                const std::string where = file + ":" + std::to_string(number);
                Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
                if (planar)
                {
                    std::istringstream fields(line);
                    std::vector<double> v;
                    std::string token;
                    while (fields >> token)
                        v.push_back(parseFiniteNumber(token, where, "x y theta"));
                    if (v.size() != 3)
                        throw Exception(where, "expected 3 numbers (x y theta) for this SE(2) problem, found " +
                                                   std::to_string(v.size()));
                    X.linear() = Eigen::AngleAxisd(v[2], Eigen::Vector3d::UnitZ()).toRotationMatrix();
                    X.translation() = Eigen::Vector3d(v[0], v[1], 0.0);
                }
                else
                    X = parsePose(line, where);
                stateFromPose(space, X, state);
                path.append(state);
            }
        }
        catch (...)
        {
            si->freeState(state);
            throw;
        }
        si->freeState(state);
        if (path.getStateCount() == 0)
            throw Exception(file, "no states in the path file");
        return path;
    }

    std::vector<double> parseRobotState(const std::string &text, const RobotModel &robot, const std::string &where)
    {
        const std::size_t dimension = robot.dimension();
        std::istringstream fields(text);
        std::vector<double> q;
        std::string token;
        while (fields >> token)
            q.push_back(parseFiniteNumber(token, where, "a state of " + std::to_string(dimension) + " numbers"));
        if (q.size() != dimension)
            throw Exception(where, "a state of this problem has " + std::to_string(dimension) +
                                       " numbers (as start.joints, or the bodies' states one after the other), "
                                       "found " + std::to_string(q.size()));
        try
        {
            std::vector<Eigen::Isometry3d> frames;  // the frames too: a state may place no frame (a zero quaternion)
            robot.framePoses(q.data(), q.size(), frames);
        }
        catch (const Exception &e)
        {
            throw Exception(where, e.what());
        }
        // A pose's quaternion within 1e-3 of unit length, as a single body's pose has always been read (parsePose()).
        for (const StateBlock &block : robot.stateBlocks())
            if (block.space == JointSpace::SE3)
            {
                const double norm = Eigen::Vector4d(q[block.first + 3], q[block.first + 4], q[block.first + 5],
                                                    q[block.first + 6]).norm();
                std::string name = block.names.front();  // "JOINT.x": the pose of JOINT
                name = name.size() > 2 && name.compare(name.size() - 2, 2, ".x") == 0 ? name.substr(0, name.size() - 2)
                                                                                      : name;
                if (std::abs(norm - 1.0) > 1e-3)
                    throw Exception(where, "quaternion (qx qy qz qw) of " + quote(name) +
                                               " is not of unit length (norm " + std::to_string(norm) + ")");
            }
        return q;
    }

    std::vector<std::vector<double>> readRobotPathFile(const std::string &file, const RobotModel &robot)
    {
        checkInputFile(file);
        std::ifstream in(file);
        if (!in)
            throw Exception(file, "cannot be read");
        std::vector<std::vector<double>> states;
        std::string text;
        for (std::size_t number = 1; std::getline(in, text); ++number)
        {
            const auto first = text.find_first_not_of(" \t\r");
            if (first != std::string::npos && text[first] != '#')
                states.push_back(parseRobotState(text, robot, file + ":" + std::to_string(number)));
        }
        if (states.empty())
            throw Exception(file, "no states in the file");
        return states;
    }
}  // namespace meshgap
