#include "meshgap/robot/Srdf.h"

#include <tinyxml2.h>

#include "meshgap/Exception.h"
#include "meshgap/InputFile.h"
#include "meshgap/Text.h"

namespace meshgap
{
    std::vector<SrdfDisabledPair> readSrdfDisabledCollisions(const std::string &path)
    {
        const std::string xml = readInputFile(path);
        tinyxml2::XMLDocument document;
        if (document.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
        {
            const int line = document.ErrorLineNum();
            throw Exception(excerpt(path) + (line > 0 ? ":" + std::to_string(line) : std::string()),
                            std::string("cannot read the SRDF: ") + document.ErrorStr());
        }
        const tinyxml2::XMLElement *robot = document.RootElement();
        if (!robot || std::string(robot->Name()) != "robot")
            throw Exception(excerpt(path), "not an SRDF: its root element is not <robot>");
        std::vector<SrdfDisabledPair> pairs;
        for (const tinyxml2::XMLElement *e = robot->FirstChildElement("disable_collisions"); e;
             e = e->NextSiblingElement("disable_collisions"))
        {
            const char *a = e->Attribute("link1"), *b = e->Attribute("link2");
            if (!a || !b)
                throw Exception(excerpt(path) + ":" + std::to_string(e->GetLineNum()),
                                "disable_collisions needs both link1 and link2");
            pairs.push_back({a, b, e->GetLineNum()});
        }
        return pairs;
    }

    void readSrdf(RobotModel &robot, const std::string &path)
    {
        for (const SrdfDisabledPair &pair : readSrdfDisabledCollisions(path))
        {
            for (const std::string &name : {pair.link1, pair.link2})
                if (robot.findLink(name) == RobotModel::NONE && robot.findFrame(name) == RobotModel::NONE)
                    throw Exception(excerpt(path) + ":" + std::to_string(pair.line),
                                    "disable_collisions names link " + quote(name) + ", which the robot does not have");
            robot.allowCollision(pair.link1, pair.link2);
        }
    }
}  // namespace meshgap
