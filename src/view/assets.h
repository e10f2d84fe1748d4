// The viewer's page template and its script (three.js and web/src/viewer.js,
// bundled by esbuild), embedded at build time by web/embed.cmake. A build
// without npm links view/no_assets.cpp instead: both strings are empty.
#pragma once

namespace sharpmesh::view_assets {

extern const char* const kTemplate;  ///< web/src/page.html
extern const char* const kScript;    ///< the bundle, or "" without a viewer

}  // namespace sharpmesh::view_assets
