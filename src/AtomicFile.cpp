#include "meshgap/AtomicFile.h"

#include <ompl/util/Console.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"

#if defined(__unix__) || defined(__APPLE__)
#include <signal.h>
#include <unistd.h>
#define MESHGAP_HAVE_POSIX_IO 1
#endif

namespace meshgap
{
    namespace
    {
        /** \brief This machine's name, as it appears in temporary file names (dots replaced, so names parse). */
        std::string hostName()
        {
            char name[256] = "host";
#ifdef MESHGAP_HAVE_POSIX_IO
            if (::gethostname(name, sizeof name - 1) != 0)
                std::strcpy(name, "host");
            name[sizeof name - 1] = '\0';
#endif
            std::string host(name);
            std::replace(host.begin(), host.end(), '.', '_');
            std::replace(host.begin(), host.end(), '/', '_');
            return host.empty() ? std::string("host") : host;
        }

        long processId()
        {
#ifdef MESHGAP_HAVE_POSIX_IO
            return static_cast<long>(::getpid());
#else
            return 0;
#endif
        }
    }  // namespace

    std::string temporaryPath(const std::string &path)
    {
        static std::atomic<unsigned long> counter{0};
        return path + ".tmp." + hostName() + "." + std::to_string(processId()) + "." + std::to_string(counter++);
    }

    void removeStaleTemporaries(const std::string &path)
    {
#ifdef MESHGAP_HAVE_POSIX_IO
        namespace fs = std::filesystem;
        const fs::path target(path);
        const std::string prefix = target.filename().string() + ".tmp." + hostName() + ".";
        std::error_code ec;
        fs::directory_iterator it(target.has_parent_path() ? target.parent_path() : fs::path("."), ec), end;
        for (; !ec && it != end; it.increment(ec))
        {
            const std::string name = it->path().filename().string();
            if (name.compare(0, prefix.size(), prefix) != 0)
                continue;
            const std::string rest = name.substr(prefix.size());  // <pid>.<n>
            const auto dot = rest.find('.');
            if (dot == 0 || dot == std::string::npos || rest.find_first_not_of("0123456789.") != std::string::npos)
                continue;
            const long pid = std::strtol(rest.substr(0, dot).c_str(), nullptr, 10);
            if (pid <= 0 || pid == processId())
                continue;
            if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
            {
                std::error_code ignored;
                if (fs::remove(it->path(), ignored))
                    OMPL_INFORM("meshgap: removed '%s', left by a writer that was killed", it->path().string().c_str());
            }
        }
#else
        (void)path;
#endif
    }

    void writeAtomically(const std::string &path, const std::function<void(const std::string &temporary)> &write)
    {
        const std::string temporary = temporaryPath(path);
        try
        {
            write(temporary);
            std::error_code ec;
            std::filesystem::rename(temporary, path, ec);
            if (ec)
                throw Exception(excerpt(path), "cannot rename " + temporary + " to it: " + ec.message());
        }
        catch (...)
        {
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw;
        }
    }

    void writeStreamAtomically(const std::string &path, const std::function<void(std::ostream &out)> &write,
                               bool binary)
    {
        writeAtomically(path,
                        [&](const std::string &temporary)
                        {
                            errno = 0;
                            std::ofstream out(temporary, binary ? std::ios::out | std::ios::binary : std::ios::out);
                            if (!out)
                                throw Exception(excerpt(path),
                                                "cannot open " + temporary + " for writing" +
                                                    (errno != 0 ? std::string(": ") + std::strerror(errno) : ""));
                            write(out);
                            out.close();
                            if (!out)
                                throw Exception(
                                    excerpt(path),
                                    "write failed" + (errno != 0 ? std::string(": ") + std::strerror(errno) : ""));
                        });
    }
}  // namespace meshgap
