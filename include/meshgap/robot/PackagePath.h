#ifndef MESHGAP_ROBOT_PACKAGE_PATH_H
#define MESHGAP_ROBOT_PACKAGE_PATH_H

#include <string>
#include <vector>

namespace meshgap
{
    /** \brief The folders ROS_PACKAGE_PATH names (split at ':', empty entries dropped); none when it is unset. */
    std::vector<std::string> rosPackagePath();

    /** \brief The file a robot description's URI names, as ROS resolves it:
        - "package://PKG/REST": the folder of package PKG, then REST. PKG is looked up in each folder D of
          \e packagePath in turn (D/PKG, D itself when its name is PKG, D/share/PKG: a source tree, a package
          folder, an install tree), then in \e baseFolder and each of its parents (the same three places), so that a
          description shipped beside its packages needs no search path;
        - "file://PATH" or an absolute path: that file;
        - a relative path: relative to \e baseFolder (the description's own folder).
        Throws meshgap::Exception naming the URI and every folder searched when no such package or file exists. */
    std::string resolveRobotUri(const std::string &uri, const std::vector<std::string> &packagePath,
                                const std::string &baseFolder);
}  // namespace meshgap

#endif
