#include "core/util/version.h"

// Generated into the build tree: only this file recompiles when the version changes.
#include "ipd_version.h"

namespace ipd {

const char* version() { return IPD_VERSION; }

}  // namespace ipd
