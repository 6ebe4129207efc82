#include "meshgap/geometry/TriangleBvh.h"  // against the flow
