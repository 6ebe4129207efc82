#ifndef MESHGAP_MESH_DISTANCE_CACHE_H
#define MESHGAP_MESH_DISTANCE_CACHE_H

#include <cstddef>
#include <cstdint>
#include <string>

#include "meshgap/mesh/SurfaceGraph.h"

namespace meshgap
{
    /** \brief xxHash64 of \e size bytes at \e data with seed \e seed, reimplemented here. Words are read in native
        byte order, so this is xxHash64 proper on little-endian machines (the tests check its published values).
        Chain calls through \e seed to hash several buffers. Used for the cache key and the payload checksum; not
        cryptographic. */
    std::uint64_t hashBytes(const void *data, std::size_t size, std::uint64_t seed = 0);

    /** \brief Content hash of \e graph: its offsets, neighbours and the exact bits of its edge lengths. Two graphs
        with the same hash are taken to have the same all-pairs table. */
    std::uint64_t graphHash(const SurfaceGraph &graph);

    /** \brief The cache file for a graph with hash \e hash: <dir>/meshgap-<16 hex digits>.dist. */
    std::string distanceCachePath(const std::string &dir, std::uint64_t hash);

    /** \brief Read an all-pairs table from \e path into \e D and \e P (numNodes^2 entries each, row-major).
        Returns false, leaving \e D and \e P unspecified, if the file is missing (silently) or fails any check:
        magic, format version, byte order, node count, graph hash, file size, payload checksum (with an OMPL_WARN
        naming the file and the failed check). The file format is described in DistanceCache.cpp. */
    bool readDistanceCache(const std::string &path, std::uint64_t hash, std::uint32_t numNodes, double *D,
                           std::uint32_t *P);

    /** \brief Write the table atomically: to a temporary file in the same folder
        (<path>.tmp.<host>.<pid>.<n>), flushed and synced, then renamed onto \e path, so a reader sees either no
        file or a complete one, also when the writer is killed. Creates the folder if needed. Returns false (with
        an OMPL_WARN) on any failure, leaving no temporary file behind; never throws for I/O errors. A writer killed
        mid-write leaves its temporary file; the next write of the same \e path removes those of this host whose
        process no longer exists. */
    bool writeDistanceCache(const std::string &path, std::uint64_t hash, std::uint32_t numNodes, const double *D,
                            const std::uint32_t *P);
}  // namespace meshgap

#endif
