#include "meshgap/InputFile.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"

namespace meshgap
{
    void checkInputFile(const std::string &path)
    {
        namespace fs = std::filesystem;
        std::error_code ec;
        const fs::file_status status = fs::status(path, ec);
        if (path.empty() || status.type() == fs::file_type::not_found)
            throw Exception(path.empty() ? std::string("''") : excerpt(path), "no such file");
        if (ec)
            throw Exception(excerpt(path), "cannot be read (" + ec.message() + ")");
        if (status.type() == fs::file_type::directory)
            throw Exception(excerpt(path), "is a folder, not a file");
        if (status.type() != fs::file_type::regular)
            throw Exception(excerpt(path), "is not a regular file (a device, a FIFO or a socket)");
        if (!std::ifstream(path).good())
            throw Exception(excerpt(path), "cannot be opened for reading");
    }

    std::string readInputFile(const std::string &path)
    {
        checkInputFile(path);
        std::ifstream in(path, std::ios::binary);
        std::ostringstream text;
        text << in.rdbuf();
        if (in.bad())
            throw Exception(excerpt(path), "cannot be read");
        return text.str();
    }
}  // namespace meshgap
