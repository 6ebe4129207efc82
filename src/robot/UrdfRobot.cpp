#include "meshgap/robot/UrdfRobot.h"

#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/InputFile.h"
#include "meshgap/Limits.h"
#include "meshgap/Text.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/robot/PackagePath.h"
#include "meshgap/robot/Primitives.h"

namespace meshgap
{
    namespace
    {
        /** \brief urdfdom's messages (console_bridge) while it parses, kept for the error rather than printed. The
            handler is process-wide, so parses take turns. */
        class ConsoleCapture : public console_bridge::OutputHandler
        {
        public:
            ConsoleCapture() : lock_(mutex())
            {
                previous_ = console_bridge::getOutputHandler();
                console_bridge::useOutputHandler(this);
            }
            ~ConsoleCapture() override { console_bridge::useOutputHandler(previous_); }
            ConsoleCapture(const ConsoleCapture &) = delete;
            ConsoleCapture &operator=(const ConsoleCapture &) = delete;

            void log(const std::string &text, console_bridge::LogLevel level, const char *, int) override
            {
                if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
                    errors_ += (errors_.empty() ? "" : "; ") + excerpt(text);
            }
            const std::string &errors() const { return errors_; }

        private:
            static std::mutex &mutex()
            {
                static std::mutex m;
                return m;
            }
            std::lock_guard<std::mutex> lock_;
            console_bridge::OutputHandler *previous_{nullptr};
            std::string errors_;
        };

        /** \brief Where in a URDF a check is: the file and the link or joint being read ("link 'upper'"). */
        struct XmlPlace
        {
            const std::string &path;
            std::string context;

            /** \brief Throws "path:line: context: <box size="0.5 0.06">: problem" for element \e e (its name and
                attributes shortened by excerpt()). */
            [[noreturn]] void fail(const tinyxml2::XMLElement *e, const std::string &problem) const
            {
                std::string text = "<" + std::string(e->Name());
                for (const tinyxml2::XMLAttribute *a = e->FirstAttribute(); a; a = a->Next())
                {
                    const std::string value = a->Value();
                    text += " " + std::string(a->Name()) + "=\"" +
                            (value.size() > 60 ? value.substr(0, 60) + "..." : value) + "\"";
                }
                throw Exception(excerpt(path) + ":" + std::to_string(e->GetLineNum()),
                                context + ": " + excerpt(text) + ">: " + problem);
            }
        };

        /** \brief The \e count numbers of attribute \e name of \e e ("0.25 0 0.1"), or none when it is absent and
            not \e required. Each must be a finite number, within MAX_MAGNITUDE unless \e anyMagnitude (an axis), and
            above zero if \e positive. Throws naming the file, line, element and problem. */
        std::vector<double> xmlNumbers(const XmlPlace &place, const tinyxml2::XMLElement *e, const char *name,
                                       std::size_t count, bool required, bool positive = false, bool anyMagnitude = false)
        {
            const char *text = e->Attribute(name);
            if (!text)
            {
                if (required)
                    place.fail(e, std::string("no ") + name + " attribute");
                return {};
            }
            std::istringstream fields(text);
            std::vector<double> values;
            std::string token;
            while (fields >> token)
            {
                double x = 0.0;
                if (!parseNumber(token, x) || !std::isfinite(x))
                    place.fail(e, std::string(name) + " has " + quote(token) + ", not a finite number");
                if (!anyMagnitude && std::abs(x) > MAX_MAGNITUDE)
                    place.fail(e, std::string(name) + " has " + excerpt(token) +
                                      ", beyond 1e12 in magnitude (the "
                                      "largest meshgap's geometry answers "
                                      "reliably)");
                if (positive && !(x > 0.0))
                    place.fail(e, std::string(name) + " must be positive, found " + excerpt(token));
                values.push_back(x);
            }
            if (values.size() != count)
                place.fail(e, std::string(name) + " needs " + std::to_string(count) +
                                  (count == 1 ? " number" : " numbers") + ", found " + std::to_string(values.size()));
            return values;
        }

        /** \brief Checks one <collision> or <visual> element of link \e link where urdfdom would drop a bad one
            with only a log message: its origin's numbers, one <geometry> holding one box, cylinder, sphere or mesh,
            and that shape's numbers (finite, sizes positive, three where three are due) and file name. */
        void checkGeometryElement(const tinyxml2::XMLElement *element, const std::string &path,
                                  const std::string &link)
        {
            const XmlPlace place{path, "link " + quote(link)};
            if (const tinyxml2::XMLElement *origin = element->FirstChildElement("origin"))
            {
                xmlNumbers(place, origin, "xyz", 3, false);
                xmlNumbers(place, origin, "rpy", 3, false);
            }
            const tinyxml2::XMLElement *geometry = element->FirstChildElement("geometry");
            const tinyxml2::XMLElement *shape = geometry ? geometry->FirstChildElement() : nullptr;
            if (!shape)
                place.fail(element, "no <geometry> with a shape in it");
            if (shape->NextSiblingElement())
                place.fail(geometry, "more than one shape in one <geometry>");
            const std::string kind = shape->Name();
            if (kind == "box")
                xmlNumbers(place, shape, "size", 3, true, true);
            else if (kind == "cylinder")
            {
                xmlNumbers(place, shape, "radius", 1, true, true);
                xmlNumbers(place, shape, "length", 1, true, true);
            }
            else if (kind == "sphere")
                xmlNumbers(place, shape, "radius", 1, true, true);
            else if (kind == "mesh")
            {
                if (!shape->Attribute("filename") || std::string(shape->Attribute("filename")).empty())
                    place.fail(shape, "a mesh without a filename");
                for (double x : xmlNumbers(place, shape, "scale", 3, false))
                    if (x == 0.0)
                        place.fail(shape, "a scale of zero");
            }
            else
                place.fail(shape, "an unknown shape (box, cylinder, sphere, mesh)");
        }

        /** \brief Checks the numbers of a joint element that urdfdom takes without a range: its origin and limits
            within MAX_MAGNITUDE (a continuous joint's limits, which bound nothing, only finite), its axis finite, its
            mimic's multiplier and offset finite. */
        void checkJointNumbers(const tinyxml2::XMLElement *joint, const std::string &path, const std::string &name,
                               const std::string &type)
        {
            const XmlPlace place{path, "joint " + quote(name)};
            if (const tinyxml2::XMLElement *origin = joint->FirstChildElement("origin"))
            {
                xmlNumbers(place, origin, "xyz", 3, false);
                xmlNumbers(place, origin, "rpy", 3, false);
            }
            if (const tinyxml2::XMLElement *axis = joint->FirstChildElement("axis"))
                xmlNumbers(place, axis, "xyz", 3, false, false, true);
            if (const tinyxml2::XMLElement *limit = joint->FirstChildElement("limit"))
            {
                xmlNumbers(place, limit, "lower", 1, false, false, type == "continuous");
                xmlNumbers(place, limit, "upper", 1, false, false, type == "continuous");
            }
            if (const tinyxml2::XMLElement *mimic = joint->FirstChildElement("mimic"))
            {
                xmlNumbers(place, mimic, "multiplier", 1, false);
                xmlNumbers(place, mimic, "offset", 1, false);
            }
        }

        /** \brief A joint element as the file writes it, for the checks urdfdom does not make (or makes silently). */
        struct XmlJoint
        {
            std::string name, type, parent, child;
            int line;
        };

        /** \brief The link names and joint elements of \e document, in document order. */
        void readElements(const tinyxml2::XMLDocument &document, const std::string &path,
                          std::vector<std::string> &links, std::vector<XmlJoint> &joints)
        {
            const tinyxml2::XMLElement *robot = document.RootElement();
            if (!robot || std::string(robot->Name()) != "robot")
                throw Exception(excerpt(path), "not a URDF: its root element is not <robot>");
            for (const tinyxml2::XMLElement *e = robot->FirstChildElement("link"); e; e = e->NextSiblingElement("link"))
            {
                links.push_back(e->Attribute("name") ? e->Attribute("name") : "");
                for (const tinyxml2::XMLElement *g = e->FirstChildElement(); g; g = g->NextSiblingElement())
                    if (std::string(g->Name()) == "collision" || std::string(g->Name()) == "visual")
                        checkGeometryElement(g, path, links.back());
            }
            for (const tinyxml2::XMLElement *e = robot->FirstChildElement("joint"); e;
                 e = e->NextSiblingElement("joint"))
            {
                const std::string where = excerpt(path) + ":" + std::to_string(e->GetLineNum());
                auto attribute = [&](const tinyxml2::XMLElement *element, const char *name, const char *what)
                {
                    if (!element || !element->Attribute(name))
                        throw Exception(where, std::string("joint without ") + what);
                    return std::string(element->Attribute(name));
                };
                XmlJoint j{attribute(e, "name", "a name"), attribute(e, "type", "a type"),
                           attribute(e->FirstChildElement("parent"), "link", "a parent link"),
                           attribute(e->FirstChildElement("child"), "link", "a child link"), e->GetLineNum()};
                checkJointNumbers(e, path, j.name, j.type);
                const auto &types = jointTypes();
                if (std::none_of(types.begin(), types.end(), [&](const JointType *t) { return j.type == t->name; }))
                    throw Exception(where, "joint " + quote(j.name) + " has an unknown type " + quote(j.type) + " (" +
                                               jointTypeNames() + ")");
                joints.push_back(j);
            }
        }

        /** \brief Throws unless \e joints join \e links into one tree: known links, at most one parent joint per
            link, no cycle, one root. */
        void checkTree(const std::string &path, const std::vector<std::string> &links,
                       const std::vector<XmlJoint> &joints)
        {
            std::map<std::string, const XmlJoint *> parentJoint;
            for (const std::string &l : links)
                parentJoint[l] = nullptr;
            for (const XmlJoint &j : joints)
            {
                const std::string where = excerpt(path) + ":" + std::to_string(j.line);
                for (const std::string &l : {j.parent, j.child})
                    if (parentJoint.count(l) == 0)
                        throw Exception(
                            where, "joint " + quote(j.name) + " names link " + quote(l) + ", which is not defined");
                if (const XmlJoint *other = parentJoint[j.child])
                    throw Exception(where, "link " + quote(j.child) + " is the child of two joints, " +
                                               quote(other->name) + " and " + quote(j.name) +
                                               ": the joints do not form a tree");
                parentJoint[j.child] = &j;
            }
            std::vector<std::string> roots;
            for (const auto &[link, joint] : parentJoint)
            {
                if (!joint)
                {
                    roots.push_back(link);
                    continue;
                }
                // Follow the parents up: a tree reaches a root within links.size() steps, a cycle never does.
                std::string at = link, cycle = link;
                for (std::size_t steps = 0; parentJoint[at]; ++steps)
                {
                    at = parentJoint[at]->parent;
                    if (steps > links.size())
                        throw Exception(excerpt(path), "the joints form a cycle through link " + quote(at) +
                                                           " (joint " + quote(parentJoint[at]->name) +
                                                           "): a URDF must be a tree");
                }
            }
            if (roots.size() != 1)
            {
                std::string names;
                for (const std::string &r : roots)
                    names += (names.empty() ? "" : ", ") + quote(r);
                throw Exception(excerpt(path), roots.empty() ? "no root link: the joints form a cycle"
                                                             : "several root links (" + names +
                                                                   "): the joints must join every link into one tree");
            }
        }

        /** \brief Throws unless urdfdom's \e model has the links and joints the file's XML names (\e links, \e joints),
            joined the same way: the two XML readers can differ (urdfdom changes a name with an unknown entity such
            as "&nt" that tinyxml2 keeps). */
        void checkSameTree(const std::string &path, const urdf::ModelInterface &model,
                           const std::vector<std::string> &links, const std::vector<XmlJoint> &joints)
        {
            auto differs = [&path](const std::string &what)
            {
                return Exception(excerpt(path),
                                 "urdfdom reads " + what +
                                     " differently from the XML (an unknown entity or a character reference in a "
                                     "name?)");
            };
            if (model.links_.size() != links.size() || model.joints_.size() != joints.size())
                throw differs("the links and joints");
            for (const std::string &l : links)
                if (!model.getLink(l))
                    throw differs("link " + quote(l));
            for (const XmlJoint &j : joints)
            {
                const urdf::JointConstSharedPtr joint = model.getJoint(j.name);
                if (!joint || joint->parent_link_name != j.parent || joint->child_link_name != j.child)
                    throw differs("joint " + quote(j.name));
            }
        }

        /** \brief Largest magnitude of a joint's origin coordinate, limit, mimic multiplier and mimic offset (metres,
            radians): far beyond any robot, and small enough that every frame of every state within the limits stays
            finite. */
        constexpr double MAX_JOINT_MAGNITUDE = 1e9;

        /** \brief Throws unless \e value (what joint \e joint of \e path gives as \e what) is at most
            MAX_JOINT_MAGNITUDE in magnitude (so not NaN). */
        void checkJointNumber(const std::string &path, const std::string &joint, const std::string &what, double value)
        {
            if (std::abs(value) <= MAX_JOINT_MAGNITUDE)
                return;
            std::ostringstream text;
            text << "joint " << quote(joint) << ": " << what << " " << value << " is not a number of magnitude at most "
                 << MAX_JOINT_MAGNITUDE;
            throw Exception(excerpt(path), text.str());
        }

        Eigen::Isometry3d toIsometry(const urdf::Pose &pose)
        {
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
                             .normalized()
                             .toRotationMatrix();
            X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
            return X;
        }

        /** \brief One geometry element's mesh in its own frame. */
        Mesh geometryMesh(const urdf::Geometry &geometry, const UrdfOptions &options, const std::string &folder)
        {
            switch (geometry.type)
            {
                case urdf::Geometry::BOX:
                {
                    const auto &box = static_cast<const urdf::Box &>(geometry);
                    return boxMesh(Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z));
                }
                case urdf::Geometry::CYLINDER:
                {
                    const auto &cylinder = static_cast<const urdf::Cylinder &>(geometry);
                    return cylinderMesh(cylinder.radius, cylinder.length, options.segments);
                }
                case urdf::Geometry::SPHERE:
                    return sphereMesh(static_cast<const urdf::Sphere &>(geometry).radius, options.segments);
                case urdf::Geometry::MESH:
                {
                    const auto &mesh = static_cast<const urdf::Mesh &>(geometry);
                    const std::vector<std::string> path =
                        options.packagePath.empty() ? rosPackagePath() : options.packagePath;
                    Mesh m = loadMesh(resolveRobotUri(mesh.filename, path, folder));
                    const Eigen::Vector3d scale(mesh.scale.x, mesh.scale.y, mesh.scale.z);
                    if (!scale.allFinite() || scale.prod() == 0.0)
                        throw Exception(mesh.filename, "the scale is zero or not finite");
                    for (Eigen::Vector3d &v : m.vertices)
                        v = v.cwiseProduct(scale);
                    if (scale.prod() < 0.0)  // a mirror turns the triangles inside out
                        for (Triangle &t : m.triangles)
                            std::swap(t[1], t[2]);
                    return m;
                }
            }
            throw Exception("URDF", "a geometry of unknown kind");
        }

        /** \brief A box, cylinder or sphere element as the solid it is, at \e pose; false for a mesh. */
        bool geometryPrimitive(const urdf::Geometry &geometry, const Eigen::Isometry3d &pose, Primitive &solid)
        {
            solid.pose = pose;
            switch (geometry.type)
            {
                case urdf::Geometry::BOX:
                {
                    const auto &box = static_cast<const urdf::Box &>(geometry);
                    solid.kind = Primitive::Kind::BOX;
                    solid.size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
                    return true;
                }
                case urdf::Geometry::CYLINDER:
                {
                    const auto &cylinder = static_cast<const urdf::Cylinder &>(geometry);
                    solid.kind = Primitive::Kind::CYLINDER;
                    solid.size = Eigen::Vector3d(cylinder.radius, cylinder.length, 0.0);
                    return true;
                }
                case urdf::Geometry::SPHERE:
                    solid.kind = Primitive::Kind::SPHERE;
                    solid.size = Eigen::Vector3d(static_cast<const urdf::Sphere &>(geometry).radius, 0.0, 0.0);
                    return true;
                default:
                    return false;
            }
        }

        /** \brief The link's collision geometry (its visual geometry when it has no collision element) merged into
            one mesh in the link frame; no triangles when it has neither. \e primitives: every element as the solid
            it is, in the link frame, when each is a box, cylinder or sphere; empty otherwise. */
        Mesh linkMesh(const urdf::Link &link, const UrdfOptions &options, const std::string &folder,
                      std::vector<Primitive> &primitives)
        {
            std::vector<std::pair<urdf::GeometrySharedPtr, urdf::Pose>> elements;
            for (const urdf::CollisionSharedPtr &c : link.collision_array)
                if (c && c->geometry)
                    elements.emplace_back(c->geometry, c->origin);
            if (elements.empty())
                for (const urdf::VisualSharedPtr &v : link.visual_array)
                    if (v && v->geometry)
                        elements.emplace_back(v->geometry, v->origin);
            std::vector<Mesh> parts;
            primitives.clear();
            bool allPrimitives = true;
            for (const auto &[geometry, origin] : elements)
            {
                parts.push_back(geometryMesh(*geometry, options, folder));
                transformMesh(parts.back(), toIsometry(origin));
                Primitive solid;
                allPrimitives = allPrimitives && geometryPrimitive(*geometry, toIsometry(origin), solid);
                primitives.push_back(solid);
            }
            if (!allPrimitives)
                primitives.clear();
            return parts.empty() ? Mesh() : mergeMeshes(parts, link.name);
        }

    }  // namespace

    /** \brief Builds a UrdfRobot, step by step. */
    struct UrdfBuilder
    {
        static void addFrames(UrdfRobot &robot, const std::string &root, const std::vector<XmlJoint> &order);
        static void addJoints(UrdfRobot &robot, const urdf::ModelInterface &model, const std::vector<XmlJoint> &order,
                              const std::string &path);
        static void resolveMimics(UrdfRobot &robot, const urdf::ModelInterface &model, const std::string &path);
        static void addLinks(UrdfRobot &robot, const urdf::ModelInterface &model, const UrdfOptions &options,
                             const std::string &path);
        /** \brief Each frame's FrameJoint (a floating base's on the root) and the state's size. */
        static void setFrameJoints(UrdfRobot &robot);
    };

    void UrdfBuilder::addFrames(UrdfRobot &robot, const std::string &root, const std::vector<XmlJoint> &order)
    {
        robot.addFrame(root, RobotModel::NONE);
        // Parent before child: place a joint's child once its parent is placed (the tree was checked).
        std::vector<bool> placed(order.size(), false);
        for (std::size_t count = 0; count < order.size();)
            for (std::size_t i = 0; i < order.size(); ++i)
            {
                const std::size_t parent = robot.findFrame(order[i].parent);
                if (placed[i] || parent == RobotModel::NONE)
                    continue;
                robot.addFrame(order[i].child, parent);
                placed[i] = true;
                ++count;
            }
    }

    void UrdfBuilder::addJoints(UrdfRobot &robot, const urdf::ModelInterface &model,
                                const std::vector<XmlJoint> &order, const std::string &path)
    {
        std::map<std::string, std::string> typeOf;  // the type each joint element names
        for (const XmlJoint &x : order)
            typeOf[x.name] = x.type;
        // Frames 1.. are the joints' children in forward-kinematics order.
        for (std::size_t f = 1; f < robot.frames().size(); ++f)
        {
            const urdf::JointConstSharedPtr joint = model.getLink(robot.frames()[f].name)->parent_joint;
            UrdfJoint j;
            j.name = joint->name;
            j.parent = robot.frames()[f].parent;
            j.child = f;
            j.origin = toIsometry(joint->parent_to_joint_origin_transform);
            if (!j.origin.linear().allFinite())
                throw Exception(excerpt(path), "joint " + quote(j.name) + ": its origin's rotation is not finite");
            for (int k = 0; k < 3; ++k)
                checkJointNumber(path, j.name, "the origin's coordinate", j.origin.translation()[k]);
            JointSpec spec;
            spec.axis = Eigen::Vector3d(joint->axis.x, joint->axis.y, joint->axis.z);
            spec.hasLimits = joint->limits != nullptr;
            spec.lower = spec.hasLimits ? joint->limits->lower : 0.0;
            spec.upper = spec.hasLimits ? joint->limits->upper : 0.0;
            try
            {
                j.joint = makeJoint(typeOf.at(j.name), spec);
            }
            catch (const Exception &e)
            {
                throw Exception(excerpt(path), "joint " + quote(j.name) + ": " + e.what());
            }
            j.axis = j.joint->axis();
            for (std::size_t k = 0; k < j.joint->size(); ++k)
            {
                if (!(j.joint->lower(k) <= j.joint->upper(k)))
                    throw Exception(excerpt(path), "joint " + quote(j.name) + ": its lower limit is above its upper limit");
                for (const double limit : {j.joint->lower(k), j.joint->upper(k)})
                    if (!std::isinf(limit))
                        checkJointNumber(path, j.name, "the limit", limit);
            }
            j.variable = RobotModel::NONE;
            j.mimics = RobotModel::NONE;
            j.multiplier = 1.0;
            j.offset = 0.0;
            robot.joints_.push_back(j);
        }
        // State order: the file's order of the movable joints that mimic none.
        std::size_t next = robot.jointOffset();
        for (const XmlJoint &x : order)
        {
            const std::size_t k = robot.findJoint(x.name);
            UrdfJoint &j = robot.joints_[k];
            if (j.joint->size() == 0 || model.getJoint(x.name)->mimic)
                continue;
            j.variable = next;
            next += j.joint->size();
            robot.variables_.insert(robot.variables_.end(), j.joint->size(), k);
        }
    }

    void UrdfBuilder::resolveMimics(UrdfRobot &robot, const urdf::ModelInterface &model, const std::string &path)
    {
        for (UrdfJoint &j : robot.joints_)
        {
            const urdf::JointConstSharedPtr joint = model.getJoint(j.name);
            if (!joint->mimic || j.joint->size() == 0)
                continue;
            if (j.joint->size() != 1)
                throw Exception(path, "joint '" + j.name + "', a " + j.joint->type() +
                                          " joint, mimics another: only a joint of one value can");
            // Follow a chain of mimic joints to the movable joint at its end, composing the affine maps.
            double multiplier = 1.0, offset = 0.0;
            urdf::JointConstSharedPtr at = joint;
            for (std::size_t steps = 0; at->mimic; ++steps)
            {
                const std::size_t k = robot.findJoint(at->mimic->joint_name);
                const bool single = k != RobotModel::NONE && robot.joints_[k].joint->size() == 1;
                if (!single || steps > robot.joints_.size())
                    throw Exception(excerpt(path), "joint " + quote(j.name) + " mimics '" + excerpt(at->mimic->joint_name) +
                                              (k == RobotModel::NONE ? "', which is not defined"
                                               : steps > robot.joints_.size()
                                                   ? "', in a cycle of mimic joints"
                                                   : "', a " + std::string(robot.joints_[k].joint->type()) +
                                                         " joint (only a joint of one value is mimicked)"));
                offset = multiplier * at->mimic->offset + offset;
                multiplier *= at->mimic->multiplier;
                at = model.getJoint(at->mimic->joint_name);
                j.mimics = k;
            }
            checkJointNumber(path, j.name, "the mimic multiplier (along its chain of mimic joints)", multiplier);
            checkJointNumber(path, j.name, "the mimic offset (along its chain of mimic joints)", offset);
            j.multiplier = multiplier;
            j.offset = offset;
        }
    }

    void UrdfBuilder::setFrameJoints(UrdfRobot &robot)
    {
        if (robot.floatingBase_)
        {
            FrameJoint base;
            base.name = "base";
            base.joint = makeJoint("floating");
            base.variable = 0;
            robot.setFrameJoint(0, base);
        }
        for (const UrdfJoint &j : robot.joints_)
        {
            FrameJoint f;
            f.name = j.name;
            f.joint = j.joint;
            f.origin = j.origin;
            f.variable = j.mimics != RobotModel::NONE ? robot.joints_[j.mimics].variable : j.variable;
            f.mimics = j.mimics != RobotModel::NONE ? robot.joints_[j.mimics].child : RobotModel::NONE;
            f.multiplier = j.multiplier;
            f.offset = j.offset;
            robot.setFrameJoint(j.child, f);
        }
        robot.setDimension(robot.jointOffset() + robot.variables_.size());
    }

    void UrdfBuilder::addLinks(UrdfRobot &robot, const urdf::ModelInterface &model, const UrdfOptions &options,
                               const std::string &path)
    {
        const std::string folder = std::filesystem::path(path).parent_path().string();
        for (std::size_t f = 0; f < robot.frames().size(); ++f)
        {
            const std::string &name = robot.frames()[f].name;
            Mesh mesh;
            std::vector<Primitive> primitives;
            try
            {
                mesh = linkMesh(*model.getLink(name), options, folder.empty() ? "." : folder, primitives);
            }
            catch (const Exception &e)
            {
                throw Exception(excerpt(path), "link " + quote(name) + ": " + e.what());
            }
            if (mesh.triangles.empty())
                continue;  // a frame only
            // Adjacent links touch by design: a new link is allowed with its nearest ancestor that has geometry.
            const std::size_t owner = f == 0 ? RobotModel::NONE : robot.ownerLink(robot.frames()[f].parent);
            if (!options.solids)
                primitives.clear();
            BodyPtr body = Body::build(std::move(mesh), std::move(primitives), options.body);
            const std::size_t link = robot.addLink(name, body, f, Eigen::Isometry3d::Identity(), false);
            if (owner != RobotModel::NONE)
                robot.allowCollision(owner, link);
        }
    }

    std::string UrdfRobot::description() const
    {
        return "URDF " + quote(name_) + (floatingBase_ ? ", floating base" : "") + ", " +
               std::to_string(variables_.size()) + " joints";
    }

    UrdfRobotPtr UrdfRobot::load(const std::string &path, const UrdfOptions &options)
    {
        const std::string xml = readInputFile(path);
        tinyxml2::XMLDocument document;
        if (document.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
            throw Exception(excerpt(path) + ":" + std::to_string(document.ErrorLineNum()),
                            std::string("cannot read the URDF: ") + document.ErrorStr());
        std::vector<std::string> linkNames;
        std::vector<XmlJoint> order;
        readElements(document, path, linkNames, order);
        checkTree(path, linkNames, order);

        urdf::ModelInterfaceSharedPtr model;
        {
            ConsoleCapture capture;
            model = urdf::parseURDF(xml);
            // urdfdom drops an element it cannot read, logs why and returns the rest: an error all the same.
            if (!model || !capture.errors().empty())
                throw Exception(excerpt(path),
                                "urdfdom rejects the URDF: " +
                                    (capture.errors().empty() ? std::string("(no reason given)")
                                                              : excerpt(capture.errors(), 4 * MAX_QUOTED)));
        }
        checkSameTree(path, *model, linkNames, order);
        UrdfRobotPtr robot(new UrdfRobot());
        robot->where_ = excerpt(path);
        robot->name_ = model->getName();
        robot->floatingBase_ = options.floatingBase;
        UrdfBuilder::addFrames(*robot, model->getRoot()->name, order);
        UrdfBuilder::addJoints(*robot, *model, order, path);
        UrdfBuilder::resolveMimics(*robot, *model, path);
        UrdfBuilder::setFrameJoints(*robot);
        UrdfBuilder::addLinks(*robot, *model, options, path);
        if (robot->links().empty())
            throw Exception(excerpt(path), "robot " + quote(robot->name_) + " has no collision geometry: none of its links has a "
                                  "<collision> or <visual> element, so there is nothing to check");
        return robot;
    }

    std::size_t UrdfRobot::findJoint(const std::string &name) const
    {
        for (std::size_t k = 0; k < joints_.size(); ++k)
            if (joints_[k].name == name)
                return k;
        return NONE;
    }
}  // namespace meshgap
