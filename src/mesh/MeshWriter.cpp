#include "meshgap/mesh/MeshWriter.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include <unistd.h>

#include "meshgap/Exception.h"

namespace meshgap
{
    void writeObj(const Mesh &mesh, const std::string &path)
    {
        const std::string temporary = path + ".tmp." + std::to_string(static_cast<long>(::getpid()));
        auto fail = [&](const std::string &what) {
            const std::string reason = errno != 0 ? std::string(": ") + std::strerror(errno) : std::string();
            std::remove(temporary.c_str());
            throw Exception(path, what + reason);
        };
        for (const Triangle &t : mesh.triangles)
            for (std::uint32_t i : t)
                if (i >= mesh.vertices.size())
                    throw Exception(path, "cannot write a triangle that uses vertex " + std::to_string(i) +
                                              " of " + std::to_string(mesh.vertices.size()));
        errno = 0;
        std::unique_ptr<std::FILE, int (*)(std::FILE *)> file(std::fopen(temporary.c_str(), "w"), &std::fclose);
        if (!file)
            throw Exception(path, std::string("cannot open for writing") +
                                      (errno != 0 ? std::string(": ") + std::strerror(errno) : std::string()));
        bool ok = std::fprintf(file.get(), "# %s: %zu vertices, %zu triangles (written by meshgap)\n",
                               mesh.source.empty() ? "mesh" : mesh.source.c_str(), mesh.vertices.size(),
                               mesh.triangles.size()) > 0;
        for (const Eigen::Vector3d &v : mesh.vertices)
            ok = ok && std::fprintf(file.get(), "v %.17g %.17g %.17g\n", v.x(), v.y(), v.z()) > 0;
        for (const Triangle &t : mesh.triangles)
            ok = ok && std::fprintf(file.get(), "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1) > 0;
        ok = ok && std::fflush(file.get()) == 0;
        std::FILE *raw = file.release();
        if (std::fclose(raw) != 0 || !ok)
            fail("write failed");
        if (std::rename(temporary.c_str(), path.c_str()) != 0)
            fail("cannot rename " + temporary + " to it");
    }
}  // namespace meshgap
