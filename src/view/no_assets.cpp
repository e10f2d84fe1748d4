// Linked when the build had no npm to bundle the viewer (see view/assets.h).
#include "view/assets.h"

namespace sharpmesh::view_assets {

const char* const kTemplate = "";
const char* const kScript = "";

}  // namespace sharpmesh::view_assets
