#ifndef MESHGAP_INPUT_FILE_H
#define MESHGAP_INPUT_FILE_H

#include <string>

namespace meshgap
{
    /** \brief The one check every reader makes before it opens a file: throws meshgap::Exception naming \e path
        unless it is a regular file (a link to one is) that can be opened for reading: "no such file", "is a folder,
        not a file", "is not a regular file (a device, a FIFO or a socket)", "cannot be opened for reading". A FIFO
        is refused before it is opened (opening one blocks until a writer comes). */
    void checkInputFile(const std::string &path);

    /** \brief The whole content of \e path, after checkInputFile(). */
    std::string readInputFile(const std::string &path);
}  // namespace meshgap

#endif
