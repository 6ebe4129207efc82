#ifndef MESHGAP_ATOMIC_FILE_H
#define MESHGAP_ATOMIC_FILE_H

#include <functional>
#include <ostream>
#include <string>

namespace meshgap
{
    /** \brief A name in the folder of \e path that no other writer (thread or process, on this or another machine
        sharing the folder) uses at the same time: <path>.tmp.<host>.<pid>.<counter>. */
    std::string temporaryPath(const std::string &path);

    /** \brief Remove the temporary files of \e path that writers killed mid-write left behind: those named by
        temporaryPath() on this machine whose process no longer exists. A live writer's file, and any file of another
        machine, is left alone. */
    void removeStaleTemporaries(const std::string &path);

    /** \brief The one way meshgap writes a file: \e write writes the whole file under the temporary name it is
        given (temporaryPath(), beside \e path), and that file is then renamed over \e path, so a reader never sees
        half a file. If \e write throws, or the rename fails, the temporary file is removed and the exception passed
        on (a failed rename throws a meshgap::Exception naming \e path). */
    void writeAtomically(const std::string &path, const std::function<void(const std::string &temporary)> &write);

    /** \brief writeAtomically() through a stream: \e write writes to \e out (opened in binary mode if \e binary);
        a stream that fails to open, write or close throws a meshgap::Exception naming \e path. */
    void writeStreamAtomically(const std::string &path, const std::function<void(std::ostream &out)> &write,
                               bool binary = false);
}  // namespace meshgap

#endif
