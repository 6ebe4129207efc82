#ifndef MESHGAP_TESTS_TEST_PCH_H
#define MESHGAP_TESTS_TEST_PCH_H

// The headers most test files include, precompiled once for meshgap_tests (tests/CMakeLists.txt, MESHGAP_TEST_PCH):
// the standard library's, gtest, Eigen, OMPL's common ones and FCL. Only third-party headers, so that a change to
// meshgap's own headers rebuilds only the files that include them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>
#ifdef MESHGAP_HAVE_FCL
#include <fcl/fcl.h>
#endif

#endif
