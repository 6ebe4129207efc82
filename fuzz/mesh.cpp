// libFuzzer entry for fuzz::mesh() (see FuzzTargets.h).
#include "FuzzTargets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    meshgap::fuzz::mesh(data, size);
    return 0;
}
