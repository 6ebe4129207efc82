#include "meshgap/robot/PackagePath.h"

#include <cstdlib>
#include <filesystem>

#include "meshgap/Exception.h"
#include "meshgap/InputFile.h"
#include "meshgap/Text.h"

namespace fs = std::filesystem;

namespace meshgap
{
    namespace
    {
        bool isFolder(const fs::path &p)
        {
            std::error_code ignored;
            return fs::is_directory(p, ignored);
        }

        /** \brief Package \e name's folder in or at \e root, or an empty path. */
        fs::path packageIn(const fs::path &root, const std::string &name)
        {
            for (const fs::path &candidate : {root / name, root, root / "share" / name})
                if ((candidate != root || root.filename() == name) && isFolder(candidate))
                    return candidate;
            return fs::path();
        }

        std::string joined(const std::vector<fs::path> &folders)
        {
            std::string text;
            for (const fs::path &f : folders)
                text += (text.empty() ? "" : ", ") + f.string();
            return text.empty() ? "(none)" : text;
        }
    }  // namespace

    std::vector<std::string> rosPackagePath()
    {
        std::vector<std::string> folders;
        const char *value = std::getenv("ROS_PACKAGE_PATH");
        if (!value)
            return folders;
        std::string text(value);
        std::size_t begin = 0;
        while (begin <= text.size())
        {
            const std::size_t end = std::min(text.find(':', begin), text.size());
            if (end > begin)
                folders.push_back(text.substr(begin, end - begin));
            begin = end + 1;
        }
        return folders;
    }

    std::string resolveRobotUri(const std::string &uri, const std::vector<std::string> &packagePath,
                                const std::string &baseFolder)
    {
        const std::string packageScheme = "package://", fileScheme = "file://";
        fs::path file;
        if (uri.compare(0, packageScheme.size(), packageScheme) == 0)
        {
            const std::string rest = uri.substr(packageScheme.size());
            const std::size_t slash = rest.find('/');
            const std::string name = rest.substr(0, slash);
            if (name.empty() || slash == std::string::npos || slash + 1 == rest.size())
                throw Exception(excerpt(uri), "a package URI needs a package name and a file (package://PACKAGE/FILE)");
            std::vector<fs::path> searched(packagePath.begin(), packagePath.end());
            for (fs::path folder = fs::absolute(baseFolder).lexically_normal();; folder = folder.parent_path())
            {
                searched.push_back(folder);
                if (folder == folder.parent_path())
                    break;
            }
            fs::path package;
            for (std::size_t i = 0; i < searched.size() && package.empty(); ++i)
                package = packageIn(searched[i], name);
            if (package.empty())
                throw Exception(excerpt(uri), "no package " + quote(name) + " in any of " + joined(searched) +
                                         " (ROS_PACKAGE_PATH or the package path, then the description's folder "
                                         "and its parents)");
            file = package / rest.substr(slash + 1);
        }
        else if (uri.compare(0, fileScheme.size(), fileScheme) == 0)
            file = uri.substr(fileScheme.size());
        else
            file = fs::path(uri).is_absolute() ? fs::path(uri) : fs::path(baseFolder) / uri;
        std::error_code ignored;
        if (!fs::exists(file, ignored))
            throw Exception(excerpt(uri), "no such file: " + excerpt(file.string()));
        try
        {
            checkInputFile(file.string());  // a folder, a FIFO or a device says what it is
        }
        catch (const Exception &e)
        {
            throw Exception(excerpt(uri), e.what());
        }
        return file.string();
    }
}  // namespace meshgap
