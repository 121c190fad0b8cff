// knoblab's version: `knoblab --version`, the provenance of stored results.
// One source, project(knoblab VERSION …) in the top CMakeLists.txt, with the
// commit the tree was built from and whether it differed from that commit:
// "0.1.0+g0123456789ab" or "0.1.0+g0123456789ab.dirty" ("0.1.0+unknown"
// outside a git checkout, unless KNOBLAB_GIT_COMMIT is given to CMake).
#pragma once

namespace knoblab {

// Defined in the generated version.cpp, so a new commit recompiles one file.
extern const char* const kVersion;

}  // namespace knoblab
