#include "adaptex/core/errors.h"
// Exceptions are header-only; this unit anchors the area library.
namespace adaptex {}
