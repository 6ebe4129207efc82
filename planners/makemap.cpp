// meshgap_makemap: writes the paper's three test scenes (Carretero & Nahon, Section IV) as meshes, poses and
// OMPL.app problem files:
//
//   battery_fixture  ORU battery (B) near an insertion pose on its fixture (A), two poses (cm, Table II)
//   hand_bowl        a hand (B) whose middle fingertip is about to touch a bowl's rim (A) (mm, Table IV)
//   handshake        two hands about to shake, B's thumb tip nearest to A's index tip (mm)
//
// and scenes that are not from the paper:
//
//   slotted_wall     a C-shaped payload (B) to pass through a wall (A) by a narrow slot (short, little clearance)
//                    or a wide one off to the side (long, four times the play): a length/clearance trade-off
//   twisted          a stress scene for the exact layer: a thin helical strip (B, three turns of long thin
//                    triangles) screwed through a helical channel of the same pitch (A) with 0.3 of play on every
//                    side; its .poses are the whole screw motion, a collision-free path close to A all the way
//   arm_fixture      a four-joint arm (URDF primitives) carrying a C-shaped payload through a window in a wall
//   swap_se3         two L-shaped bodies swapping rooms through one door, in SE(3)
//   swap_se2         the same in SE(2)
//   car_chicane      OMPL.app's kinematic car through a chicane of two walls (control = kinematic_car)
//   blimp_window     OMPL.app's blimp through a window above its start and goal (control = blimp)
//   quadrotor_window OMPL.app's quadrotor through a window in a wall (control = quadrotor)
//
// Each body is built from planar-faced polyhedra (planners/support/Shapes.h) gridded at the paper's grid sizes. Each
// pose is designed by hand and then slid along one direction until the exact (triangle-triangle) distance between
// the meshes equals the paper's "exact" minimum distance for that example (Tables III, V, VI). Each scene's .cfg is
// also a planning problem that forces a clearance trade-off (its straight line from start to goal runs into A; see
//
// The parts: makemap/MapScene.h (a scene and the helpers its recipes share), PaperScenes.cpp, SlottedWall.cpp,
// Twisted.cpp, RobotMaps.cpp, ControlMaps.cpp (the recipes), MapWriter.cpp (writes, reports and checks a scene).

#include <algorithm>
#include <boost/program_options.hpp>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "CliMain.h"
#include "makemap/MapScene.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"

namespace po = boost::program_options;
using namespace meshgap::makemap;

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, [](int ac, char **av) {
        const std::vector<std::pair<std::string, std::function<Scene()>>> scenes = {
            {"battery_fixture", batteryFixture}, {"hand_bowl", handBowl}, {"handshake", handshake},
            {"slotted_wall", slottedWallScene}, {"twisted", twistedScene}};
        const std::vector<std::pair<std::string, std::function<void(const std::filesystem::path &)>>> robotMaps = {
            {"arm_fixture", writeArmFixture}, {"swap_se3", writeSwapSE3}, {"swap_se2", writeSwapSE2},
            {"car_chicane", writeCarChicane}, {"blimp_window", writeBlimpWindow},
            {"quadrotor_window", writeQuadrotorWindow}};
        po::options_description options("meshgap_makemap: write the paper's test scenes (meshes, poses, OMPL.app "
                                        "problems)");
        std::string out, which;
        options.add_options()("help,h", "show this help")(
            "out", po::value<std::string>(&out)->required(), "output directory (one sub-directory per scene)")(
            "scene", po::value<std::string>(&which)->default_value("all"),
            "battery_fixture, hand_bowl, handshake, slotted_wall, twisted, arm_fixture, swap_se3, swap_se2, "
            "car_chicane, blimp_window, quadrotor_window or all")(
            "battery-grid", po::value<double>(&batteryGrid),
            "largest edge of the battery and fixture meshes in cm (default 5 sqrt 2, Table II's grid; a larger value "
            "gives coarse meshes for adaptive node sizing to refine)");
        po::variables_map vm;
        if (!meshgap::cli::parseCommandLine(ac, av, options, vm))
            return 0;
        std::vector<std::string> names;
        for (const auto &scene : scenes)
            names.push_back(scene.first);
        for (const auto &map : robotMaps)
            names.push_back(map.first);
        if (which != "all" && std::find(names.begin(), names.end(), which) == names.end())
            throw meshgap::Exception(
                "--scene", "unknown scene " + meshgap::quote(which) + " (valid: " + meshgap::joinNames(names) + ", all)");
        for (const auto &scene : scenes)
            if (which == "all" || which == scene.first)
                writeScene(scene.second(), std::filesystem::path(out) / scene.first);
        for (const auto &map : robotMaps)
            if (which == "all" || which == map.first)
                map.second(std::filesystem::path(out) / map.first);
        return 0;
    });
}

