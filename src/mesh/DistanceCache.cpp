#include "meshgap/mesh/DistanceCache.h"

#include <ompl/util/Console.h>

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <system_error>

#include "meshgap/AtomicFile.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#define MESHGAP_HAVE_POSIX_IO 1
#endif

/* Cache file format, version 1 (native byte order, checked through the byte-order mark):

     offset  size  field
          0     8  magic "MGAPDIST"
          8     4  format version (uint32) = 1
         12     4  byte-order mark (uint32) = 0x01020304
         16     8  node count n (uint64)
         24     8  graph hash (uint64), graphHash() of the SurfaceGraph the table belongs to
         32     8  payload size in bytes (uint64) = 12 n^2
         40     8  payload checksum (uint64) = hashBytes(P, 4 n^2, hashBytes(D, 8 n^2, 0))
         48  8n^2  D, row-major doubles: D[u * n + v] = distance from u to v
   48 + 8n^2  4n^2  P, row-major uint32: P[u * n + v] = node before v on the path from u; UINT32_MAX if unreachable

   The file size must be exactly 48 + 12 n^2. */

namespace meshgap
{
    namespace
    {
        constexpr char MAGIC[8] = {'M', 'G', 'A', 'P', 'D', 'I', 'S', 'T'};
        constexpr std::uint32_t FORMAT_VERSION = 1;
        constexpr std::uint32_t BYTE_ORDER_MARK = 0x01020304u;

        struct CacheHeader
        {
            char magic[8];
            std::uint32_t version;
            std::uint32_t byteOrder;
            std::uint64_t nodeCount;
            std::uint64_t graphHash;
            std::uint64_t payloadBytes;
            std::uint64_t payloadChecksum;
        };
        static_assert(sizeof(CacheHeader) == 48, "cache header must have no padding");

        // Chunk size for fread/fwrite: large transfers in pieces, so a short count is easy to report.
        constexpr std::size_t IO_CHUNK = std::size_t(64) << 20;

        constexpr std::uint64_t P1 = 0x9E3779B185EBCA87ull;
        constexpr std::uint64_t P2 = 0xC2B2AE3D27D4EB4Full;
        constexpr std::uint64_t P3 = 0x165667B19E3779F9ull;
        constexpr std::uint64_t P4 = 0x85EBCA77C2B2AE63ull;
        constexpr std::uint64_t P5 = 0x27D4EB2F165667C5ull;

        inline std::uint64_t rotl(std::uint64_t x, int r)
        {
            return (x << r) | (x >> (64 - r));
        }

        inline std::uint64_t read64(const unsigned char *p)
        {
            std::uint64_t v;
            std::memcpy(&v, p, sizeof v);
            return v;
        }

        inline std::uint32_t read32(const unsigned char *p)
        {
            std::uint32_t v;
            std::memcpy(&v, p, sizeof v);
            return v;
        }

        inline std::uint64_t mixRound(std::uint64_t acc, std::uint64_t input)
        {
            acc += input * P2;
            acc = rotl(acc, 31);
            return acc * P1;
        }

        inline std::uint64_t mergeRound(std::uint64_t acc, std::uint64_t value)
        {
            acc ^= mixRound(0, value);
            return acc * P1 + P4;
        }

        std::uint64_t payloadChecksum(std::uint32_t numNodes, const double *D, const std::uint32_t *P)
        {
            const std::size_t entries = std::size_t(numNodes) * numNodes;
            return hashBytes(P, entries * sizeof(std::uint32_t), hashBytes(D, entries * sizeof(double), 0));
        }

        std::uint64_t payloadBytes(std::uint32_t numNodes)
        {
            return std::uint64_t(numNodes) * numNodes * (sizeof(double) + sizeof(std::uint32_t));
        }

        /** \brief Read exactly \e size bytes, in chunks. */
        bool readAll(std::FILE *f, void *data, std::size_t size)
        {
            auto *p = static_cast<unsigned char *>(data);
            while (size > 0)
            {
                const std::size_t chunk = std::min(size, IO_CHUNK);
                if (std::fread(p, 1, chunk, f) != chunk)
                    return false;
                p += chunk;
                size -= chunk;
            }
            return true;
        }

        /** \brief Write exactly \e size bytes, in chunks. */
        bool writeAll(std::FILE *f, const void *data, std::size_t size)
        {
            const auto *p = static_cast<const unsigned char *>(data);
            while (size > 0)
            {
                const std::size_t chunk = std::min(size, IO_CHUNK);
                if (std::fwrite(p, 1, chunk, f) != chunk)
                    return false;
                p += chunk;
                size -= chunk;
            }
            return true;
        }

        void rejectCache(const std::string &path, const std::string &why)
        {
            OMPL_WARN("meshgap: ignoring distance cache '%s' (%s); rebuilding it", path.c_str(), why.c_str());
        }
    }  // namespace

    std::uint64_t hashBytes(const void *data, std::size_t size, std::uint64_t seed)
    {
        const auto *p = static_cast<const unsigned char *>(data);
        const unsigned char *const end = p + size;
        std::uint64_t h;
        if (size >= 32)
        {
            std::uint64_t v1 = seed + P1 + P2, v2 = seed + P2, v3 = seed, v4 = seed - P1;
            const unsigned char *const limit = end - 32;
            do
            {
                v1 = mixRound(v1, read64(p));
                v2 = mixRound(v2, read64(p + 8));
                v3 = mixRound(v3, read64(p + 16));
                v4 = mixRound(v4, read64(p + 24));
                p += 32;
            } while (p <= limit);
            h = rotl(v1, 1) + rotl(v2, 7) + rotl(v3, 12) + rotl(v4, 18);
            h = mergeRound(h, v1);
            h = mergeRound(h, v2);
            h = mergeRound(h, v3);
            h = mergeRound(h, v4);
        }
        else
            h = seed + P5;
        h += static_cast<std::uint64_t>(size);
        for (; p + 8 <= end; p += 8)
            h = rotl(h ^ mixRound(0, read64(p)), 27) * P1 + P4;
        if (p + 4 <= end)
        {
            h = rotl(h ^ (std::uint64_t(read32(p)) * P1), 23) * P2 + P3;
            p += 4;
        }
        for (; p < end; ++p)
            h = rotl(h ^ (std::uint64_t(*p) * P5), 11) * P1;
        h ^= h >> 33;
        h *= P2;
        h ^= h >> 29;
        h *= P3;
        h ^= h >> 32;
        return h;
    }

    std::uint64_t graphHash(const SurfaceGraph &graph)
    {
        const auto &offsets = graph.offsets();
        const auto &neighbours = graph.neighbours();
        const auto &lengths = graph.lengths();
        // Each array's length goes in through hashBytes (it adds the byte count), so the split points matter too.
        std::uint64_t h = hashBytes(offsets.data(), offsets.size() * sizeof(std::uint32_t), 0x6d65736867617031ull);
        h = hashBytes(neighbours.data(), neighbours.size() * sizeof(std::uint32_t), h);
        return hashBytes(lengths.data(), lengths.size() * sizeof(double), h);
    }

    std::string distanceCachePath(const std::string &dir, std::uint64_t hash)
    {
        char name[40];
        std::snprintf(name, sizeof name, "meshgap-%016" PRIx64 ".dist", hash);
        return (std::filesystem::path(dir) / name).string();
    }

    namespace
    {
        /** \brief Why a cache file's \e header (of a file of \e fileSize bytes) does not fit a mesh graph of \e
           numNodes nodes and \e hash; empty if it does. */
        std::string headerMismatch(const CacheHeader &header, std::uint64_t hash, std::uint32_t numNodes,
                                   std::uintmax_t fileSize)
        {
            if (std::memcmp(header.magic, MAGIC, sizeof MAGIC) != 0)
                return "bad magic: not a meshgap distance table";
            if (header.version != FORMAT_VERSION)
                return "format version " + std::to_string(header.version) + ", expected " +
                       std::to_string(FORMAT_VERSION);
            if (header.byteOrder != BYTE_ORDER_MARK)
                return "written with another byte order";
            if (header.nodeCount != numNodes)
                return "stale: " + std::to_string(header.nodeCount) + " nodes, the mesh has " +
                       std::to_string(numNodes);
            if (header.graphHash != hash)
                return "stale: written for a different mesh graph (hash mismatch)";
            const std::uint64_t expectedPayload = payloadBytes(numNodes);
            if (header.payloadBytes != expectedPayload || fileSize != sizeof(CacheHeader) + expectedPayload)
                return "truncated or padded: " + std::to_string(fileSize) + " bytes, expected " +
                       std::to_string(sizeof(CacheHeader) + expectedPayload);
            return "";
        }
    }  // namespace

    bool readDistanceCache(const std::string &path, std::uint64_t hash, std::uint32_t numNodes, double *D,
                           std::uint32_t *P)
    {
        std::error_code ec;
        if (!std::filesystem::exists(path, ec))
            return false;
        const std::uintmax_t fileSize = std::filesystem::file_size(path, ec);
        if (ec)
        {
            rejectCache(path, "cannot get its size: " + ec.message());
            return false;
        }
        if (fileSize < sizeof(CacheHeader))
        {
            rejectCache(path, "shorter than its header");
            return false;
        }

        std::FILE *f = std::fopen(path.c_str(), "rb");
        if (f == nullptr)
        {
            rejectCache(path, std::string("cannot open it: ") + std::strerror(errno));
            return false;
        }
        struct Closer
        {
            std::FILE *f;
            ~Closer() { std::fclose(f); }
        } closer{f};

        CacheHeader header;
        if (!readAll(f, &header, sizeof header))
        {
            rejectCache(path, "cannot read its header");
            return false;
        }
        const std::string mismatch = headerMismatch(header, hash, numNodes, fileSize);
        if (!mismatch.empty())
        {
            rejectCache(path, mismatch);
            return false;
        }
        const std::size_t entries = std::size_t(numNodes) * numNodes;
        if (!readAll(f, D, entries * sizeof(double)) || !readAll(f, P, entries * sizeof(std::uint32_t)))
        {
            rejectCache(path, "cannot read its payload");
            return false;
        }
        if (payloadChecksum(numNodes, D, P) != header.payloadChecksum)
        {
            rejectCache(path, "corrupt: payload checksum mismatch");
            return false;
        }
        return true;
    }

    bool writeDistanceCache(const std::string &path, std::uint64_t hash, std::uint32_t numNodes, const double *D,
                            const std::uint32_t *P)
    {
        std::error_code ec;
        const std::filesystem::path dir = std::filesystem::path(path).parent_path();
        if (!dir.empty())
        {
            std::filesystem::create_directories(dir, ec);
            if (ec)
            {
                OMPL_WARN("meshgap: cannot create distance cache folder '%s' (%s); the table is not cached",
                          dir.string().c_str(), ec.message().c_str());
                return false;
            }
        }

        removeStaleTemporaries(path);

        CacheHeader header;
        std::memcpy(header.magic, MAGIC, sizeof MAGIC);
        header.version = FORMAT_VERSION;
        header.byteOrder = BYTE_ORDER_MARK;
        header.nodeCount = numNodes;
        header.graphHash = hash;
        header.payloadBytes = payloadBytes(numNodes);
        header.payloadChecksum = payloadChecksum(numNodes, D, P);

        try
        {
            writeAtomically(path,
                            [&](const std::string &tmp)
                            {
                                std::FILE *f = std::fopen(tmp.c_str(), "wb");
                                if (f == nullptr)
                                    throw Exception(excerpt(path),
                                                    "cannot create " + quote(tmp) + ": " + std::strerror(errno));
                                const std::size_t entries = std::size_t(numNodes) * numNodes;
                                bool ok = writeAll(f, &header, sizeof header) &&
                                          writeAll(f, D, entries * sizeof(double)) &&
                                          writeAll(f, P, entries * sizeof(std::uint32_t)) && std::fflush(f) == 0;
#ifdef MESHGAP_HAVE_POSIX_IO
                                ok = ok && ::fsync(::fileno(f)) == 0;
#endif
                                const int savedErrno = errno;
                                if (std::fclose(f) != 0)
                                    ok = false;
                                if (!ok)
                                    throw Exception(excerpt(path),
                                                    "writing " + quote(tmp) + " failed: " + std::strerror(savedErrno));
                            });
        }
        catch (const std::exception &e)
        {
            OMPL_WARN("meshgap: cannot write distance cache (%s); the table is not cached", e.what());
            return false;
        }
        return true;
    }
}  // namespace meshgap
