#include "meshgap/mesh/Mesh.h"
#include "meshgap/scene/Scene.h"  // against the flow: the check must fail on this line
