#include "meshgap/robot/MoveItScene.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/InputFile.h"
#include "meshgap/Text.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/robot/PackagePath.h"
#include "meshgap/robot/Primitives.h"
#include "meshgap/robot/Srdf.h"
#include "meshgap/robot/UrdfRobot.h"

namespace meshgap
{
    namespace
    {
        namespace fs = std::filesystem;

        /** \brief A named joint value and where it is given. */
        struct JointValue
        {
            std::string name, where;
            double value;
        };

        /** \brief One YAML file: its root, and how errors name its entries ("file:line", "entry: problem"). */
        class YamlFile
        {
        public:
            explicit YamlFile(const std::string &path) : path_(path)
            {
                checkInputFile(path);
                try
                {
                    root_ = YAML::LoadFile(path);
                }
                catch (const YAML::Exception &e)
                {
                    throw Exception(at(e.mark), "cannot read the YAML: " + e.msg);
                }
                if (!root_.IsMap())
                    throw Exception(excerpt(path), "not a YAML map (a moveit_msgs message)");
            }
            const YAML::Node &root() const { return root_; }
            const std::string &path() const { return path_; }
            std::string at(const YAML::Mark &mark) const
            {
                return excerpt(path_) + (mark.line >= 0 ? ":" + std::to_string(mark.line + 1) : std::string());
            }
            [[noreturn]] void fail(const YAML::Node &node, const std::string &entry, const std::string &what) const
            {
                throw Exception(node ? at(node.Mark()) : path_, entry + ": " + what);
            }
            /** \brief \e node[key] when it is a map with that key, else an undefined node (false). */
            static YAML::Node child(const YAML::Node &node, const char *key)
            {
                return node && node.IsMap() && node[key] ? node[key] : YAML::Node(YAML::NodeType::Undefined);
            }
            /** \brief \e node[key] as child() gives it, checked to be a map when it is given (\e entry names it). */
            YAML::Node section(const YAML::Node &node, const char *key, const std::string &entry) const
            {
                const YAML::Node found = child(node, key);
                if (found && !found.IsNull() && !found.IsMap())
                    fail(found, entry, "is not a map");
                return found;
            }
            double number(const YAML::Node &node, const std::string &entry) const
            {
                if (!node || !node.IsScalar())
                    fail(node, entry, "is not a number");
                try
                {
                    const double v = node.as<double>();
                    if (!std::isfinite(v))
                        fail(node, entry, "is not finite");
                    return v;
                }
                catch (const YAML::Exception &)
                {
                    fail(node, entry, quote(node.Scalar()) + " is not a number");
                }
            }
            std::string text(const YAML::Node &node, const std::string &entry) const
            {
                if (!node || !node.IsScalar())
                    fail(node, entry, "is not a text");
                return node.Scalar();
            }
            /** \brief \e node as a sequence (empty when absent). */
            std::vector<YAML::Node> list(const YAML::Node &node, const std::string &entry) const
            {
                std::vector<YAML::Node> items;
                if (!node || node.IsNull())
                    return items;
                if (!node.IsSequence())
                    fail(node, entry, "is not a list");
                for (const YAML::Node &item : node)
                    items.push_back(item);
                return items;
            }
            /** \brief \e count numbers: a list, or a map of \e fields ("xyzw"). */
            std::vector<double> numbers(const YAML::Node &node, const std::string &entry, const char *fields) const
            {
                const std::size_t count = std::string(fields).size();
                std::vector<double> out;
                if (node && node.IsMap())
                    for (std::size_t k = 0; k < count; ++k)
                        out.push_back(number(node[std::string(1, fields[k])], entry + "." + fields[k]));
                else
                    for (const YAML::Node &item : list(node, entry))
                        out.push_back(number(item, entry + "[" + std::to_string(out.size()) + "]"));
                if (out.size() != count)
                    fail(node, entry, "has " + std::to_string(out.size()) + " numbers, not " + std::to_string(count));
                return out;
            }
            /** \brief A geometry_msgs/Pose (position, orientation x y z w); identity when absent. An all-zero
                quaternion is the identity, as MoveIt takes it. */
            Eigen::Isometry3d pose(const YAML::Node &node, const std::string &entry) const
            {
                Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
                if (!node || node.IsNull())
                    return X;
                if (!node.IsMap())
                    fail(node, entry, "is not a pose (position, orientation)");
                const YAML::Node position = child(node, "position"), orientation = child(node, "orientation");
                if (position)
                {
                    const std::vector<double> p = numbers(position, entry + ".position", "xyz");
                    X.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
                }
                if (orientation)
                    X.linear() = rotation(numbers(orientation, entry + ".orientation", "xyzw"), orientation,
                                          entry + ".orientation");
                return X;
            }
            Eigen::Matrix3d rotation(const std::vector<double> &q, const YAML::Node &node,
                                     const std::string &entry) const
            {
                const Eigen::Quaterniond r(q[3], q[0], q[1], q[2]);
                if (r.norm() == 0.0)
                    return Eigen::Matrix3d::Identity();
                if (std::abs(r.norm() - 1.0) > 1e-3)
                    fail(node, entry, "the quaternion is not of unit length (norm " + std::to_string(r.norm()) + ")");
                return r.normalized().toRotationMatrix();
            }

        private:
            std::string path_;
            YAML::Node root_;
        };

        /** \brief The names and values of a sensor_msgs/JointState. */
        std::vector<JointValue> jointState(const YamlFile &file, const YAML::Node &node, const std::string &entry)
        {
            std::vector<JointValue> values;
            const std::vector<YAML::Node> names = file.list(YamlFile::child(node, "name"), entry + ".name");
            const std::vector<YAML::Node> positions =
                file.list(YamlFile::child(node, "position"), entry + ".position");
            if (names.size() != positions.size())
                file.fail(node, entry, std::to_string(names.size()) + " names but " +
                                           std::to_string(positions.size()) + " positions");
            for (std::size_t k = 0; k < names.size(); ++k)
            {
                const std::string item = entry + ".position[" + std::to_string(k) + "]";
                values.push_back({file.text(names[k], entry + ".name[" + std::to_string(k) + "]"),
                                  file.at(positions[k].Mark()) + ": " + item, file.number(positions[k], item)});
            }
            return values;
        }

        /** \brief The default state: every joint at 0, or the middle of its limits when 0 is outside them (a
            floating joint's rotation the identity). */
        std::vector<double> defaultState(const UrdfRobot &robot)
        {
            std::vector<double> q;
            for (std::size_t k = 0; k < robot.variables().size(); ++k)
            {
                const UrdfJoint &j = robot.joints()[robot.variables()[k]];
                q.push_back(j.joint->neutral(robot.jointOffset() + k - j.variable));
            }
            return q;
        }

        /** \brief Set the named joints of \e q (UrdfRobot state order); checks names and limits. */
        void applyJoints(const UrdfRobot &robot, const std::vector<JointValue> &values, std::vector<double> &q)
        {
            for (const JointValue &v : values)
            {
                const std::size_t index = robot.findJoint(v.name);
                if (index == RobotModel::NONE)
                    throw Exception(v.where, "robot " + quote(robot.name()) + " has no joint " + quote(v.name));
                const UrdfJoint &j = robot.joints()[index];
                if (j.joint->size() == 0 && v.value != 0.0)
                    throw Exception(v.where, "joint " + quote(v.name) + " is fixed in the URDF, but is given " +
                                                 std::to_string(v.value));
                if (j.joint->size() > 1)
                    throw Exception(v.where, "joint '" + v.name + "' is a " + j.joint->type() + " joint of " +
                                                 std::to_string(j.joint->size()) +
                                                 " values, which a joint state's one position cannot set");
                if (j.variable == RobotModel::NONE)
                    continue;  // fixed (at 0), or a mimic joint: follows its joint
                const double lower = j.joint->lower(0), upper = j.joint->upper(0);
                if (v.value < lower || v.value > upper)
                {
                    std::ostringstream text;
                    text << "joint " << quote(v.name) << " = " << v.value << " is outside its limits [" << lower << ", "
                         << upper << "]";
                    throw Exception(v.where, text.str());
                }
                q[j.variable - robot.jointOffset()] = v.value;
            }
        }

        /** \brief Reads a scene's collision objects into the problem's obstacles. */
        class WorldReader
        {
        public:
            WorldReader(const YamlFile &file, const UrdfRobot &robot, const std::vector<double> &state,
                        const MoveItFiles &files, const BodyOptions &options, RobotProblem &problem)
              : file_(file), robot_(robot), files_(files), options_(options), problem_(problem)
            {
                robot.framePoses(state.data(), state.size(), frames_);
                for (const YAML::Node &t : file.list(YamlFile::child(file.root(), "fixed_frame_transforms"),
                                                     "fixed_frame_transforms"))
                    fixedFrame(t);
            }

            void read()
            {
                const YAML::Node world = file_.section(file_.root(), "world", "world");
                const YAML::Node octomap = YamlFile::child(YamlFile::child(world, "octomap"), "octomap");
                if (YamlFile::child(octomap, "data") && YamlFile::child(octomap, "data").size() > 0)
                    file_.fail(octomap, "world.octomap", "an octomap is not read (give the obstacles as objects)");
                const YAML::Node attached =
                    YamlFile::child(YamlFile::child(file_.root(), "robot_state"), "attached_collision_objects");
                if (attached && attached.size() > 0)
                    file_.fail(attached, "robot_state.attached_collision_objects", "attached objects are not read");
                std::size_t k = 0;
                for (const YAML::Node &object : file_.list(YamlFile::child(world, "collision_objects"),
                                                           "world.collision_objects"))
                    readObject(object, "world.collision_objects[" + std::to_string(k++) + "]");
            }

        private:
            void fixedFrame(const YAML::Node &t)
            {
                const std::string entry = "fixed_frame_transforms";
                const std::string child = file_.text(YamlFile::child(t, "child_frame_id"), entry + ".child_frame_id");
                const YAML::Node transform = YamlFile::child(t, "transform");
                Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
                if (const YAML::Node p = YamlFile::child(transform, "translation"))
                {
                    const std::vector<double> v = file_.numbers(p, entry + ".transform.translation", "xyz");
                    X.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
                }
                if (const YAML::Node r = YamlFile::child(transform, "rotation"))
                    X.linear() = file_.rotation(file_.numbers(r, entry + ".transform.rotation", "xyzw"), r,
                                                entry + ".transform.rotation");
                fixed_[child] = X;
            }

            /** \brief The world pose of frame \e id (an object's header.frame_id). */
            Eigen::Isometry3d frame(const std::string &id, const YAML::Node &node, const std::string &entry) const
            {
                const std::string name = !id.empty() && id[0] == '/' ? id.substr(1) : id;
                if (name.empty())
                    return Eigen::Isometry3d::Identity();
                if (fixed_.count(name))
                    return fixed_.at(name);
                const std::size_t f = robot_.findFrame(name);
                if (f != RobotModel::NONE)
                    return frames_[f];
                if (name == "world")
                    return Eigen::Isometry3d::Identity();
                file_.fail(node, entry,
                           "unknown frame " + quote(id) +
                               " (neither a fixed frame of the scene nor a link "
                               "of robot " +
                               quote(robot_.name()) + ")");
            }

            /** \brief The primitive \e p as a circumscribed mesh in its own frame, and as the solid it is (its pose
                left to the caller). */
            Mesh primitive(const YAML::Node &p, const std::string &entry, Primitive &solid) const;
            Mesh mesh(const YAML::Node &m, const std::string &entry) const;
            void readObject(const YAML::Node &object, const std::string &entry);

            const YamlFile &file_;
            const UrdfRobot &robot_;
            const MoveItFiles &files_;
            const BodyOptions &options_;
            RobotProblem &problem_;
            std::vector<Eigen::Isometry3d> frames_;
            std::map<std::string, Eigen::Isometry3d> fixed_;
        };

        Mesh WorldReader::primitive(const YAML::Node &p, const std::string &entry, Primitive &solid) const
        {
            static const std::map<std::string, int> names = {{"box", 1}, {"sphere", 2}, {"cylinder", 3}, {"cone", 4}};
            const YAML::Node typeNode = YamlFile::child(p, "type");
            const std::string type = file_.text(typeNode, entry + ".type");
            int kind = 0;
            if (names.count(type))
                kind = names.at(type);
            else if (type.size() == 1 && type[0] >= '1' && type[0] <= '4')
                kind = type[0] - '0';
            else
                file_.fail(typeNode, entry + ".type",
                           "unknown primitive type " + quote(type) + " (box, sphere, cylinder, cone, or 1 to 4)");
            const YAML::Node dimensions = YamlFile::child(p, "dimensions");
            std::vector<double> d;
            for (const YAML::Node &n : file_.list(dimensions, entry + ".dimensions"))
                d.push_back(file_.number(n, entry + ".dimensions[" + std::to_string(d.size()) + "]"));
            const std::size_t needed = kind == 1 ? 3 : kind == 2 ? 1 : 2;
            if (d.size() != needed)
                file_.fail(dimensions ? dimensions : p, entry + ".dimensions",
                           std::to_string(d.size()) + " numbers; a " + type + " takes " + std::to_string(needed) +
                               (kind == 1 ? " (x y z)" : kind == 2 ? " (radius)" : " (height radius)"));
            static const Primitive::Kind kinds[] = {Primitive::Kind::BOX, Primitive::Kind::SPHERE,
                                                    Primitive::Kind::CYLINDER, Primitive::Kind::CONE};
            solid.kind = kinds[kind - 1];
            solid.size = kind == 1 ? Eigen::Vector3d(d[0], d[1], d[2]) :
                         kind == 2 ? Eigen::Vector3d(d[0], 0.0, 0.0) :
                                     Eigen::Vector3d(d[1], d[0], 0.0);
            try
            {
                if (kind == 1)
                    return boxMesh(Eigen::Vector3d(d[0], d[1], d[2]));
                if (kind == 2)
                    return sphereMesh(d[0], files_.segments);
                return kind == 3 ? cylinderMesh(d[1], d[0], files_.segments) : coneMesh(d[1], d[0], files_.segments);
            }
            catch (const Exception &e)
            {
                file_.fail(dimensions, entry + ".dimensions", e.what());
            }
        }

        Mesh WorldReader::mesh(const YAML::Node &m, const std::string &entry) const
        {
            if (const YAML::Node resource = YamlFile::child(m, "resource"))
            {
                const std::string uri = file_.text(resource, entry + ".resource");
                Mesh loaded;
                try
                {
                    const std::vector<std::string> path =
                        files_.packagePath.empty() ? rosPackagePath() : files_.packagePath;
                    const std::string folder = fs::path(file_.path()).parent_path().string();
                    loaded = loadMesh(resolveRobotUri(uri, path, folder.empty() ? "." : folder));
                }
                catch (const Exception &e)
                {
                    file_.fail(resource, entry + ".resource", e.what());
                }
                if (const YAML::Node scale = YamlFile::child(m, "scale"))
                {
                    const std::vector<double> s = file_.numbers(scale, entry + ".scale", "xyz");
                    if (!(s[0] > 0 && s[1] > 0 && s[2] > 0))
                        file_.fail(scale, entry + ".scale", "is not positive");
                    for (Eigen::Vector3d &v : loaded.vertices)
                        v = v.cwiseProduct(Eigen::Vector3d(s[0], s[1], s[2]));
                }
                return loaded;
            }
            Mesh out;
            out.source = file_.path() + " " + entry;
            for (const YAML::Node &v : file_.list(YamlFile::child(m, "vertices"), entry + ".vertices"))
            {
                const std::vector<double> p = file_.numbers(v, entry + ".vertices[]", "xyz");
                out.vertices.emplace_back(p[0], p[1], p[2]);
            }
            for (const YAML::Node &t : file_.list(YamlFile::child(m, "triangles"), entry + ".triangles"))
            {
                const YAML::Node indices = t.IsMap() ? YamlFile::child(t, "vertex_indices") : t;
                const std::vector<double> i = file_.numbers(indices, entry + ".triangles[].vertex_indices", "abc");
                Triangle tri;
                for (int k = 0; k < 3; ++k)
                {
                    if (!(i[k] >= 0 && i[k] < out.vertices.size() && i[k] == std::floor(i[k])))
                        file_.fail(indices, entry + ".triangles",
                                   "vertex index " + std::to_string(static_cast<long long>(i[k])) +
                                       " is not one of the " + std::to_string(out.vertices.size()) + " vertices");
                    tri[k] = static_cast<std::uint32_t>(i[k]);
                }
                out.triangles.push_back(tri);
            }
            if (out.triangles.empty())
                file_.fail(m, entry, "a mesh without triangles (vertices and triangles, or a resource)");
            return out;
        }

        void WorldReader::readObject(const YAML::Node &object, const std::string &where)
        {
            if (!object.IsMap())
                file_.fail(object, where, "is not a collision object");
            const std::string id = file_.text(YamlFile::child(object, "id"), where + ".id");
            const std::string entry = where + " (" + quote(id) + ")";
            const YAML::Node header = file_.section(object, "header", entry + ".header");
            const YAML::Node frameId = YamlFile::child(header, "frame_id");
            const Eigen::Isometry3d X_WO =
                frame(frameId ? file_.text(frameId, entry + ".header.frame_id") : "", frameId, entry) *
                file_.pose(YamlFile::child(object, "pose"), entry + ".pose");
            if (const YAML::Node op = YamlFile::child(object, "operation"))
                if (op.Scalar() != "0" && op.Scalar() != "ADD" && op.Scalar() != "add")
                    file_.fail(op, entry + ".operation", quote(op.Scalar()) + ": only ADD (0) is read");
            for (const char *kind : {"primitives", "meshes"})
            {
                const bool isPrimitive = kind[0] == 'p';
                const std::string posesKey = isPrimitive ? "primitive_poses" : "mesh_poses";
                const std::vector<YAML::Node> shapes = file_.list(YamlFile::child(object, kind), entry + "." + kind);
                const std::vector<YAML::Node> poses =
                    file_.list(YamlFile::child(object, posesKey.c_str()), entry + "." + posesKey);
                if (shapes.size() != poses.size())
                    file_.fail(object, entry, std::to_string(shapes.size()) + " " + kind + " but " +
                                                  std::to_string(poses.size()) + " " + posesKey);
                for (std::size_t k = 0; k < shapes.size(); ++k)
                {
                    const std::string item = entry + "." + kind + "[" + std::to_string(k) + "]";
                    std::vector<Primitive> solids(isPrimitive ? 1 : 0);
                    Mesh m = isPrimitive ? primitive(shapes[k], item, solids[0]) : mesh(shapes[k], item);
                    const Eigen::Isometry3d X_WS =
                        X_WO * file_.pose(poses[k], entry + "." + posesKey + "[" + std::to_string(k) + "]");
                    transformMesh(m, X_WS);
                    for (Primitive &solid : solids)
                        solid.pose = X_WS;
                    try
                    {
                        problem_.obstacles.push_back(Body::build(std::move(m), std::move(solids), options_));
                    }
                    catch (const Exception &e)
                    {
                        file_.fail(shapes[k], item, e.what());
                    }
                    problem_.obstacleNames.push_back(id);
                }
            }
        }

        /** \brief One row of entry_values: a list of booleans or {enabled: [...]}. */
        std::vector<bool> acmRow(const YamlFile &file, const YAML::Node &row, const std::string &entry)
        {
            const YAML::Node values = row.IsMap() ? YamlFile::child(row, "enabled") : row;
            std::vector<bool> out;
            for (const YAML::Node &v : file.list(values, entry))
            {
                bool b = false;
                if (!v.IsScalar() || !YAML::convert<bool>::decode(v, b))
                    file.fail(v, entry,
                              (v.IsScalar() ? quote(v.Scalar()) : std::string("'?'")) + " is not true or false");
                out.push_back(b);
            }
            return out;
        }

        /** \brief Allow the pair (\e a, \e b) of names: two links, or a link and an object. */
        void allowPair(UrdfRobot &robot, RobotProblem &problem, const std::string &a, const std::string &b)
        {
            const bool aRobot = robot.findLink(a) != RobotModel::NONE || robot.findFrame(a) != RobotModel::NONE;
            const bool bRobot = robot.findLink(b) != RobotModel::NONE || robot.findFrame(b) != RobotModel::NONE;
            if (aRobot && bRobot)
            {
                robot.allowCollision(a, b);
                return;
            }
            if (aRobot == bRobot)
                return;  // two objects (never checked against each other), or a name neither robot nor scene has
            const std::string &link = aRobot ? a : b, &object = aRobot ? b : a;
            for (std::size_t i = 0; i < robot.links().size(); ++i)
                if (robot.links()[i].name == link || robot.frames()[robot.links()[i].frame].name == link)
                    for (std::size_t o = 0; o < problem.obstacleNames.size(); ++o)
                        if (problem.obstacleNames[o] == object)
                            problem.allowedObstacles.emplace_back(i, o);
        }

        /** \brief The allowed collision matrix. */
        void readAcm(const YamlFile &file, UrdfRobot &robot, RobotProblem &problem)
        {
            const std::string entry = "allowed_collision_matrix";
            const YAML::Node acm = file.section(file.root(), "allowed_collision_matrix", entry);
            std::vector<std::string> names;
            for (const YAML::Node &n : file.list(YamlFile::child(acm, "entry_names"), entry + ".entry_names"))
                names.push_back(file.text(n, entry + ".entry_names[]"));
            const std::vector<YAML::Node> rows =
                file.list(YamlFile::child(acm, "entry_values"), entry + ".entry_values");
            if (rows.size() != names.size())
                file.fail(acm, entry, std::to_string(names.size()) + " entry_names but " +
                                          std::to_string(rows.size()) + " rows of entry_values");
            std::vector<std::string> everything;
            for (const YAML::Node &n :
                 file.list(YamlFile::child(acm, "default_entry_names"), entry + ".default_entry_names"))
                everything.push_back(file.text(n, entry + ".default_entry_names[]"));
            const std::set<std::string> objects(problem.obstacleNames.begin(), problem.obstacleNames.end());
            for (std::size_t r = 0; r < rows.size(); ++r)
            {
                const std::string rowEntry = entry + ".entry_values[" + std::to_string(r) + "]";
                const std::vector<bool> row = acmRow(file, rows[r], rowEntry);
                if (row.size() != names.size())
                    file.fail(rows[r], rowEntry, std::to_string(row.size()) + " values for " +
                                                     std::to_string(names.size()) + " entry_names");
                for (std::size_t c = 0; c < row.size(); ++c)
                    if (row[c] && c != r)
                        allowPair(robot, problem, names[r], names[c]);
            }
            const YAML::Node defaults = YamlFile::child(acm, "default_entry_values");
            const std::vector<bool> allowed = acmRow(file, defaults, entry + ".default_entry_values");
            if (allowed.size() != everything.size())
                file.fail(defaults ? defaults : acm, entry + ".default_entry_values",
                          std::to_string(allowed.size()) + " values for " + std::to_string(everything.size()) +
                              " default_entry_names");
            for (std::size_t k = 0; k < everything.size(); ++k)
                if (allowed[k])
                {
                    for (std::size_t i = 0; i < robot.links().size(); ++i)
                        allowPair(robot, problem, everything[k], robot.links()[i].name);
                    for (const std::string &o : objects)
                        allowPair(robot, problem, everything[k], o);
                }
            std::vector<LinkPair> &pairs = problem.allowedObstacles;
            std::sort(pairs.begin(), pairs.end());
            pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
        }

        /** \brief The request's start and goal over the scene's state \e q. */
        void readRequest(const std::string &path, const UrdfRobot &robot, RobotProblem &problem)
        {
            const YamlFile file(path);
            const YAML::Node start = file.section(file.root(), "start_state", "start_state");
            applyJoints(robot,
                        jointState(file, file.section(start, "joint_state", "start_state.joint_state"),
                                   "start_state.joint_state"),
                        problem.start);
            const std::vector<YAML::Node> goals =
                file.list(YamlFile::child(file.root(), "goal_constraints"), "goal_constraints");
            if (goals.empty())
                return;
            for (const char *other : {"position_constraints", "orientation_constraints", "visibility_constraints"})
                if (YamlFile::child(goals[0], other) && YamlFile::child(goals[0], other).size() > 0)
                    file.fail(goals[0][other], std::string("goal_constraints[0].") + other,
                              "only joint constraints are read");
            std::vector<JointValue> goal;
            std::size_t k = 0;
            for (const YAML::Node &c : file.list(YamlFile::child(goals[0], "joint_constraints"),
                                                 "goal_constraints[0].joint_constraints"))
            {
                const std::string entry = "goal_constraints[0].joint_constraints[" + std::to_string(k++) + "]";
                goal.push_back({file.text(YamlFile::child(c, "joint_name"), entry + ".joint_name"),
                                file.at(c.Mark()) + ": " + entry,
                                file.number(YamlFile::child(c, "position"), entry + ".position")});
            }
            if (goal.empty())
                file.fail(goals[0], "goal_constraints[0]", "no joint constraints");
            problem.goal = problem.start;
            applyJoints(robot, goal, *problem.goal);
        }
    }  // namespace

    UrdfRobotPtr readMoveItRobot(const MoveItFiles &files, const BodyOptions &options)
    {
        if (files.urdf.empty())
            throw Exception("MoveIt problem", "needs a URDF");
        UrdfOptions urdfOptions;
        urdfOptions.packagePath = files.packagePath;
        urdfOptions.segments = files.segments;
        urdfOptions.body = options;
        const UrdfRobotPtr robot = UrdfRobot::load(files.urdf, urdfOptions);
        if (!files.srdf.empty())
            readSrdf(*robot, files.srdf);
        return robot;
    }

    RobotProblem readMoveItProblem(const MoveItFiles &files, const BodyOptions &options)
    {
        const UrdfRobotPtr robot =
            files.robot ? std::make_shared<UrdfRobot>(*files.robot) : readMoveItRobot(files, options);
        RobotProblem problem;
        problem.file = !files.request.empty() ? files.request : !files.scene.empty() ? files.scene : files.urdf;
        if (problem.file.empty())
            throw Exception("MoveIt problem", "no files");
        problem.name = fs::path(problem.file).stem().string();
        problem.scene = files.scene;
        problem.request = files.request;
        problem.start = defaultState(*robot);
        if (!files.scene.empty())
        {
            const YamlFile file(files.scene);
            const YAML::Node state = file.section(file.section(file.root(), "robot_state", "robot_state"),
                                                  "joint_state", "robot_state.joint_state");
            applyJoints(*robot, jointState(file, state, "robot_state.joint_state"), problem.start);
            WorldReader(file, *robot, problem.start, files, options, problem).read();
            readAcm(file, *robot, problem);
        }
        if (!files.request.empty())
            readRequest(files.request, *robot, problem);
        problem.robot = robot;
        problem.urdf = true;
        return problem;
    }
}  // namespace meshgap
